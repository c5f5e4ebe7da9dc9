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

// The shader stages (vertex, and fragment unless depth/stencil only); the modules are destroyed
// once the pipeline exists.
namespace {
struct Stages {
  std::vector<VkShaderModule> modules;
  std::vector<VkPipelineShaderStageCreateInfo> infos;
};
}  // namespace

static void createStages(GpuContext& ctx, const GraphicsPipelineDesc& d, const VkSpecializationInfo* spec, Stages& out) {
  auto addStage = [&](VkShaderStageFlagBits stage, Shader name) {
    VkShaderModule m = createShaderModule(ctx, name);
    out.modules.push_back(m);
    VkPipelineShaderStageCreateInfo s{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
    s.stage = stage;
    s.module = m;
    s.pName = "main";
    s.pSpecializationInfo = spec;
    out.infos.push_back(s);
  };
  addStage(VK_SHADER_STAGE_VERTEX_BIT, d.vertexShader);
  if (d.fragmentShader != Shader::None) addStage(VK_SHADER_STAGE_FRAGMENT_BIT, d.fragmentShader);
}

// Vertex input: the scene's Vertex (only the locations the shader reads), positions alone (vec3
// at location 0), or none. `info` points into the struct: fill it in place.
namespace {
struct VertexInputState {
  VkVertexInputBindingDescription binding{};
  std::vector<VkVertexInputAttributeDescription> attributes;
  VkPipelineVertexInputStateCreateInfo info{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
};
}  // namespace

static void vertexInputState(const GraphicsPipelineDesc& d, VertexInputState& out) {
  const VkVertexInputAttributeDescription attrs[] = {
      {0, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, position)},
      {1, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, normal)},
      {2, 0, VK_FORMAT_R32G32_SFLOAT, offsetof(Vertex, uv0)},
      {3, 0, VK_FORMAT_R32G32_SFLOAT, offsetof(Vertex, uv1)},
      {4, 0, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(Vertex, tangent)},
  };
  if (d.vertexInput == VertexInput::SceneVertex) {
    out.binding = {0, sizeof(Vertex), VK_VERTEX_INPUT_RATE_VERTEX};
    for (uint32_t i = 0; i < 5; ++i)
      if (d.vertexAttributes & (1u << i)) out.attributes.push_back(attrs[i]);
  } else if (d.vertexInput == VertexInput::Position) {
    out.binding = {0, sizeof(float) * 3, VK_VERTEX_INPUT_RATE_VERTEX};
    out.attributes = {attrs[0]};  // location 0, vec3 at offset 0
  } else {
    return;
  }
  out.info.vertexBindingDescriptionCount = 1;
  out.info.pVertexBindingDescriptions = &out.binding;
  out.info.vertexAttributeDescriptionCount = uint32_t(out.attributes.size());
  out.info.pVertexAttributeDescriptions = out.attributes.data();
}

// Colour blending per attachment, and raster-order attachment access where asked and supported.
namespace {
struct BlendStates {
  std::vector<VkPipelineColorBlendAttachmentState> attachments;
  VkPipelineColorBlendStateCreateInfo info{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
};
}  // namespace

static void blendState(const GpuContext& ctx, const GraphicsPipelineDesc& d, BlendStates& out) {
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
    out.attachments.push_back(s);
  }
  out.info.attachmentCount = uint32_t(out.attachments.size());
  out.info.pAttachments = out.attachments.data();
  if (d.rasterOrderColor && ctx.features.rasterOrderAttachmentAccess)
    out.info.flags |= VK_PIPELINE_COLOR_BLEND_STATE_CREATE_RASTERIZATION_ORDER_ATTACHMENT_ACCESS_BIT_EXT;
}

// Dynamic state: viewport, scissor, cull mode, front face and stencil reference always; depth
// bias and stencil masks when the pipeline uses them.
namespace {
struct DynamicStates {
  std::vector<VkDynamicState> states;
  VkPipelineDynamicStateCreateInfo info{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
};
}  // namespace

static void dynamicState(const GraphicsPipelineDesc& d, DynamicStates& out) {
  out.states = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR, VK_DYNAMIC_STATE_CULL_MODE,
                VK_DYNAMIC_STATE_FRONT_FACE, VK_DYNAMIC_STATE_STENCIL_REFERENCE};
  if (d.depthBias) out.states.push_back(VK_DYNAMIC_STATE_DEPTH_BIAS);
  if (d.dynamicStencilMasks) {
    out.states.push_back(VK_DYNAMIC_STATE_STENCIL_COMPARE_MASK);
    out.states.push_back(VK_DYNAMIC_STATE_STENCIL_WRITE_MASK);
  }
  out.info.dynamicStateCount = uint32_t(out.states.size());
  out.info.pDynamicStates = out.states.data();
}

VkPipeline createGraphicsPipeline(GpuContext& ctx, const GraphicsPipelineDesc& d) {
  SpecData spec(d.spec);
  Stages stages;
  createStages(ctx, d, &spec.info, stages);
  VertexInputState vi;
  vertexInputState(d, vi);
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
  BlendStates cb;
  blendState(ctx, d, cb);
  DynamicStates dy;
  dynamicState(d, dy);

  VkGraphicsPipelineCreateInfo ci{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
  ci.stageCount = uint32_t(stages.infos.size());
  ci.pStages = stages.infos.data();
  ci.pVertexInputState = &vi.info;
  ci.pInputAssemblyState = &ia;
  ci.pViewportState = &vp;
  ci.pRasterizationState = &rs;
  ci.pMultisampleState = &ms;
  ci.pDepthStencilState = &ds;
  ci.pColorBlendState = &cb.info;
  ci.pDynamicState = &dy.info;
  ci.layout = d.layout;
  ci.renderPass = d.renderPass;
  ci.subpass = d.subpass;
  VkPipeline pipeline;
  VK_CHECK(vkCreateGraphicsPipelines(ctx.device, VK_NULL_HANDLE, 1, &ci, nullptr, &pipeline));
  setName(ctx, uint64_t(pipeline), VK_OBJECT_TYPE_PIPELINE, d.name.empty() ? nullptr : d.name.c_str());
  for (auto m : stages.modules) vkDestroyShaderModule(ctx.device, m, nullptr);
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

namespace gb {

VkDescriptorSetLayout createSetLayout(GpuContext& ctx, const std::vector<VkDescriptorSetLayoutBinding>& bindings,
                                      VkDescriptorSetLayoutCreateFlags flags, const char* name) {
  VkDescriptorSetLayoutCreateInfo ci{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  ci.flags = flags;
  ci.bindingCount = uint32_t(bindings.size());
  ci.pBindings = bindings.data();
  VkDescriptorSetLayout l;
  VK_CHECK(vkCreateDescriptorSetLayout(ctx.device, &ci, nullptr, &l));
  setName(ctx, uint64_t(l), VK_OBJECT_TYPE_DESCRIPTOR_SET_LAYOUT, name);
  return l;
}

}  // namespace gb
