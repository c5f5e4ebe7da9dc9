// Graphics pipelines of the mode tables (frame.h): vertex input per draw kind, culling off (the depth
// test decides), depth/stencil state from the Draw, per-attachment colour write masks, dynamic
// viewport/scissor (and stencil reference where the stencil is used).
#include <vector>

#include "frame.h"

namespace zoo {

namespace {

void vertex_input(DrawKind kind, std::vector<VkVertexInputAttributeDescription>& attrs,
                  VkVertexInputBindingDescription& binding) {
  binding = {0, sizeof(Vertex), VK_VERTEX_INPUT_RATE_VERTEX};
  if (kind == DrawKind::fullscreen) return;
  attrs.push_back({0, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, pos)});
  if (kind == DrawKind::markers) return;
  attrs.push_back({1, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, normal)});
  attrs.push_back({2, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, tangent)});
  attrs.push_back({3, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, bitangent)});
  attrs.push_back({4, 0, VK_FORMAT_R32G32_SFLOAT, offsetof(Vertex, uv)});
}

VkPipelineDepthStencilStateCreateInfo depth_state(const Draw& d) {
  VkPipelineDepthStencilStateCreateInfo ds{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
  ds.depthTestEnable = d.depth_test;
  ds.depthWriteEnable = d.depth_write;
  ds.depthCompareOp = d.depth_op;
  ds.stencilTestEnable = d.stencil != StencilUse::none;
  VkStencilOpState s{};
  s.failOp = s.depthFailOp = VK_STENCIL_OP_KEEP;
  if (d.stencil == StencilUse::test_floor) {
    s.passOp = VK_STENCIL_OP_KEEP;
    s.compareOp = VK_COMPARE_OP_EQUAL;
    s.compareMask = 0x01;  // the floor bit
    s.writeMask = 0;
  } else {
    s.passOp = VK_STENCIL_OP_REPLACE;
    s.compareOp = VK_COMPARE_OP_ALWAYS;
    s.compareMask = s.writeMask = 0xff;
  }
  ds.front = ds.back = s;
  ds.maxDepthBounds = 1;
  return ds;
}

}  // namespace

VkPipeline make_pipeline(const Gpu& g, const Pass& pass, const Draw& draw, VkRenderPass rp, VkPipelineLayout layout) {
  VkShaderModule vs = make_shader(g, draw.vs.words, draw.vs.bytes), fs = make_shader(g, draw.fs.words, draw.fs.bytes);
  VkPipelineShaderStageCreateInfo stages[2] = {{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO},
                                               {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO}};
  stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT, stages[0].module = vs, stages[0].pName = "main";
  stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT, stages[1].module = fs, stages[1].pName = "main";
  std::vector<VkVertexInputAttributeDescription> attrs;
  VkVertexInputBindingDescription binding;
  vertex_input(draw.kind, attrs, binding);
  VkPipelineVertexInputStateCreateInfo vi{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
  vi.vertexBindingDescriptionCount = attrs.empty() ? 0 : 1;
  vi.pVertexBindingDescriptions = &binding;
  vi.vertexAttributeDescriptionCount = uint32_t(attrs.size());
  vi.pVertexAttributeDescriptions = attrs.data();
  VkPipelineInputAssemblyStateCreateInfo ia{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
  ia.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
  VkPipelineViewportStateCreateInfo vp{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
  vp.viewportCount = vp.scissorCount = 1;
  VkPipelineRasterizationStateCreateInfo rs{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
  rs.polygonMode = VK_POLYGON_MODE_FILL;
  rs.cullMode = VK_CULL_MODE_NONE;
  rs.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
  rs.lineWidth = 1;
  VkPipelineMultisampleStateCreateInfo ms{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
  ms.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
  const VkPipelineDepthStencilStateCreateInfo ds = depth_state(draw);
  std::vector<VkPipelineColorBlendAttachmentState> blend;
  for (const Attachment& a : pass.attachments) {
    if (is_depth(a.format)) continue;
    VkPipelineColorBlendAttachmentState b{};
    const bool on = draw.color_mask >> blend.size() & 1u;
    b.colorWriteMask = on ? VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT | VK_COLOR_COMPONENT_B_BIT |
                                VK_COLOR_COMPONENT_A_BIT
                          : 0;
    blend.push_back(b);
  }
  VkPipelineColorBlendStateCreateInfo cb{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
  cb.attachmentCount = uint32_t(blend.size());
  cb.pAttachments = blend.data();
  std::vector<VkDynamicState> dyn = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
  if (draw.stencil != StencilUse::none) dyn.push_back(VK_DYNAMIC_STATE_STENCIL_REFERENCE);
  VkPipelineDynamicStateCreateInfo dy{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
  dy.dynamicStateCount = uint32_t(dyn.size());
  dy.pDynamicStates = dyn.data();
  VkGraphicsPipelineCreateInfo ci{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
  ci.stageCount = 2;
  ci.pStages = stages;
  ci.pVertexInputState = &vi;
  ci.pInputAssemblyState = &ia;
  ci.pViewportState = &vp;
  ci.pRasterizationState = &rs;
  ci.pMultisampleState = &ms;
  ci.pDepthStencilState = &ds;
  ci.pColorBlendState = &cb;
  ci.pDynamicState = &dy;
  ci.layout = layout;
  ci.renderPass = rp;
  VkPipeline pipeline;
  ZOO_VK(vkCreateGraphicsPipelines(g.device, VK_NULL_HANDLE, 1, &ci, nullptr, &pipeline));
  vkDestroyShaderModule(g.device, vs, nullptr);
  vkDestroyShaderModule(g.device, fs, nullptr);
  return pipeline;
}

}  // namespace zoo
