// Pipeline creation from GraphicsPipelineDesc; shader lookup in the embedded registry.
#include "renderer/vk/pipeline.h"

#include "renderer/core/vertex.h"
#include "renderer/vk/check.h"
#include "renderer/vk/debug_utils.h"

namespace gb {

VkShaderModule createShaderModule(GpuContext& ctx, Shader shader) {
  GB_ASSERT(shader != Shader::None);
  auto code = shaderCode(shader);
  VkShaderModuleCreateInfo ci{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
  ci.codeSize = code.size() * sizeof(uint32_t);
  ci.pCode = code.data();
  VkShaderModule m;
  VK_CHECK(vkCreateShaderModule(ctx.device, &ci, nullptr, &m));
  setName(ctx, uint64_t(m), VK_OBJECT_TYPE_SHADER_MODULE, shaderName(shader));
  return m;
}

std::vector<uint32_t> specValues(std::span<const SpecConstant> spec) {
  std::vector<uint32_t> v;
  for (const SpecConstant& c : spec) v.push_back(c.value);
  return v;
}

struct SpecData {
  std::vector<VkSpecializationMapEntry> entries;
  std::vector<uint32_t> values;
  VkSpecializationInfo info{};
  explicit SpecData(std::span<const SpecConstant> spec) {
    for (size_t i = 0; i < spec.size(); ++i) {
      entries.push_back({spec[i].id, uint32_t(i * sizeof(uint32_t)), sizeof(uint32_t)});
      values.push_back(spec[i].value);
    }
    info.mapEntryCount = uint32_t(entries.size());
    info.pMapEntries = entries.data();
    info.dataSize = values.size() * sizeof(uint32_t);
    info.pData = values.data();
  }
};

VkPipeline createGraphicsPipeline(GpuContext& ctx, const GraphicsPipelineDesc& d) {
  SpecData spec(d.spec);
  std::vector<VkPipelineShaderStageCreateInfo> stages;
  std::vector<VkShaderModule> modules;
  auto addStage = [&](VkShaderStageFlagBits stage, Shader name) {
    VkShaderModule m = createShaderModule(ctx, name);
    modules.push_back(m);
    VkPipelineShaderStageCreateInfo s{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
    s.stage = stage;
    s.module = m;
    s.pName = "main";
    s.pSpecializationInfo = &spec.info;
    stages.push_back(s);
  };
  addStage(VK_SHADER_STAGE_VERTEX_BIT, d.vertexShader);
  if (d.fragmentShader != Shader::None) addStage(VK_SHADER_STAGE_FRAGMENT_BIT, d.fragmentShader);

  VkVertexInputBindingDescription binding{0, sizeof(Vertex), VK_VERTEX_INPUT_RATE_VERTEX};
  VkVertexInputAttributeDescription attrs[] = {
      {0, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, position)},
      {1, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, normal)},
      {2, 0, VK_FORMAT_R32G32_SFLOAT, offsetof(Vertex, uv0)},
      {3, 0, VK_FORMAT_R32G32_SFLOAT, offsetof(Vertex, uv1)},
      {4, 0, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(Vertex, tangent)},
  };
  VkVertexInputBindingDescription positionBinding{0, sizeof(float) * 3, VK_VERTEX_INPUT_RATE_VERTEX};
  VkPipelineVertexInputStateCreateInfo vi{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
  std::vector<VkVertexInputAttributeDescription> used;
  for (uint32_t i = 0; i < 5; ++i)
    if (d.vertexAttributes & (1u << i)) used.push_back(attrs[i]);
  if (d.vertexInput == VertexInput::SceneVertex) {
    vi.vertexBindingDescriptionCount = 1;
    vi.pVertexBindingDescriptions = &binding;
    vi.vertexAttributeDescriptionCount = uint32_t(used.size());
    vi.pVertexAttributeDescriptions = used.data();
  } else if (d.vertexInput == VertexInput::Position) {
    vi.vertexBindingDescriptionCount = 1;
    vi.pVertexBindingDescriptions = &positionBinding;
    vi.vertexAttributeDescriptionCount = 1;
    vi.pVertexAttributeDescriptions = attrs;  // location 0, vec3 at offset 0
  }
  VkPipelineInputAssemblyStateCreateInfo ia{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
  ia.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
  VkPipelineViewportStateCreateInfo vp{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
  vp.viewportCount = 1;
  vp.scissorCount = 1;
  VkPipelineRasterizationStateCreateInfo rs{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
  rs.depthClampEnable = d.depthClamp && ctx.features.depthClamp;
  rs.polygonMode = VK_POLYGON_MODE_FILL;
  rs.lineWidth = 1.0f;
  rs.depthBiasEnable = d.depthBias;
  VkPipelineMultisampleStateCreateInfo ms{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
  ms.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
  VkPipelineDepthStencilStateCreateInfo ds{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
  ds.depthTestEnable = d.depthTest;
  ds.depthWriteEnable = d.depthWrite;
  ds.depthCompareOp = d.depthCompare;
  ds.stencilTestEnable = d.stencilTest;
  ds.front = d.stencil;
  ds.back = d.separateBackStencil ? d.stencilBack : d.stencil;
  std::vector<VkPipelineColorBlendAttachmentState> blends;
  for (auto& b : d.colorBlend) {
    VkPipelineColorBlendAttachmentState s{};
    s.blendEnable = b.enable;
    s.srcColorBlendFactor = b.src;
    s.dstColorBlendFactor = b.dst;
    s.colorBlendOp = VK_BLEND_OP_ADD;
    s.srcAlphaBlendFactor = b.srcAlpha;
    s.dstAlphaBlendFactor = b.dstAlpha;
    s.alphaBlendOp = VK_BLEND_OP_ADD;
    s.colorWriteMask = b.writeMask;
    blends.push_back(s);
  }
  VkPipelineColorBlendStateCreateInfo cb{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
  cb.attachmentCount = uint32_t(blends.size());
  cb.pAttachments = blends.data();
  if (d.rasterOrderColor && ctx.features.rasterOrderAttachmentAccess)
    cb.flags |= VK_PIPELINE_COLOR_BLEND_STATE_CREATE_RASTERIZATION_ORDER_ATTACHMENT_ACCESS_BIT_EXT;
  std::vector<VkDynamicState> dyn = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR, VK_DYNAMIC_STATE_CULL_MODE,
                                     VK_DYNAMIC_STATE_FRONT_FACE, VK_DYNAMIC_STATE_STENCIL_REFERENCE};
  if (d.depthBias) dyn.push_back(VK_DYNAMIC_STATE_DEPTH_BIAS);
  if (d.dynamicStencilMasks) {
    dyn.push_back(VK_DYNAMIC_STATE_STENCIL_COMPARE_MASK);
    dyn.push_back(VK_DYNAMIC_STATE_STENCIL_WRITE_MASK);
  }
  VkPipelineDynamicStateCreateInfo dy{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
  dy.dynamicStateCount = uint32_t(dyn.size());
  dy.pDynamicStates = dyn.data();

  VkGraphicsPipelineCreateInfo ci{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
  ci.stageCount = uint32_t(stages.size());
  ci.pStages = stages.data();
  ci.pVertexInputState = &vi;
  ci.pInputAssemblyState = &ia;
  ci.pViewportState = &vp;
  ci.pRasterizationState = &rs;
  ci.pMultisampleState = &ms;
  ci.pDepthStencilState = &ds;
  ci.pColorBlendState = &cb;
  ci.pDynamicState = &dy;
  ci.layout = d.layout;
  ci.renderPass = d.renderPass;
  ci.subpass = d.subpass;
  VkPipeline pipeline;
  VK_CHECK(vkCreateGraphicsPipelines(ctx.device, VK_NULL_HANDLE, 1, &ci, nullptr, &pipeline));
  setName(ctx, uint64_t(pipeline), VK_OBJECT_TYPE_PIPELINE, d.name.empty() ? nullptr : d.name.c_str());
  for (auto m : modules) vkDestroyShaderModule(ctx.device, m, nullptr);
  return pipeline;
}

VkPipeline createComputePipeline(GpuContext& ctx, Shader shader, std::span<const SpecConstant> specs,
                                 VkPipelineLayout layout) {
  SpecData spec(specs);
  VkShaderModule m = createShaderModule(ctx, shader);
  VkComputePipelineCreateInfo ci{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
  ci.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
  ci.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
  ci.stage.module = m;
  ci.stage.pName = "main";
  ci.stage.pSpecializationInfo = &spec.info;
  ci.layout = layout;
  VkPipeline pipeline;
  VK_CHECK(vkCreateComputePipelines(ctx.device, VK_NULL_HANDLE, 1, &ci, nullptr, &pipeline));
  setName(ctx, uint64_t(pipeline), VK_OBJECT_TYPE_PIPELINE, shaderName(shader));
  vkDestroyShaderModule(ctx.device, m, nullptr);
  return pipeline;
}

}  // namespace gb
