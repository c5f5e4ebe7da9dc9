// tiler_deferred's pipeline helpers (vk.h): descriptor set and pipeline layouts, the raster pipelines
// (static viewport and scissor, reverse-Z depth GREATER, no culling, no blending) and compute pipelines.
#include "vk.h"

namespace td {

VkDescriptorSetLayout make_set_layout(const gpu& g, const std::vector<VkDescriptorType>& types,
                                      VkShaderStageFlags stages) {
  std::vector<VkDescriptorSetLayoutBinding> bindings(types.size());
  for (size_t i = 0; i < types.size(); ++i) bindings[i] = {uint32_t(i), types[i], 1, stages, nullptr};
  VkDescriptorSetLayoutCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO;
  info.bindingCount = uint32_t(bindings.size());
  info.pBindings = bindings.data();
  VkDescriptorSetLayout l;
  TD_CHECK(vkCreateDescriptorSetLayout(g.device, &info, nullptr, &l));
  return l;
}

VkPipelineLayout make_pipeline_layout(const gpu& g, const std::vector<VkDescriptorSetLayout>& sets,
                                      uint32_t push_bytes, VkShaderStageFlags push_stages) {
  const VkPushConstantRange range{push_stages, 0, push_bytes};
  VkPipelineLayoutCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO;
  info.setLayoutCount = uint32_t(sets.size());
  info.pSetLayouts = sets.data();
  info.pushConstantRangeCount = push_bytes ? 1 : 0;
  info.pPushConstantRanges = push_bytes ? &range : nullptr;
  VkPipelineLayout l;
  TD_CHECK(vkCreatePipelineLayout(g.device, &info, nullptr, &l));
  return l;
}

VkPipeline make_raster_pipeline(const gpu& g, const raster_desc& d) {
  VkPipelineShaderStageCreateInfo stages[2]{};
  for (int i = 0; i < 2; ++i) {
    stages[i].sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
    stages[i].stage = i == 0 ? VK_SHADER_STAGE_VERTEX_BIT : VK_SHADER_STAGE_FRAGMENT_BIT;
    stages[i].module = i == 0 ? d.vert : d.frag;
    stages[i].pName = "main";
  }
  // The scene's vertices: vec3 position at 0, vec3 normal at 12, 24 bytes each.
  const VkVertexInputBindingDescription binding{0, 24, VK_VERTEX_INPUT_RATE_VERTEX};
  const VkVertexInputAttributeDescription attributes[2] = {{0, 0, VK_FORMAT_R32G32B32_SFLOAT, 0},
                                                           {1, 0, VK_FORMAT_R32G32B32_SFLOAT, 12}};
  VkPipelineVertexInputStateCreateInfo vertex{};
  vertex.sType = VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO;
  if (d.vertices) {
    vertex.vertexBindingDescriptionCount = 1;
    vertex.pVertexBindingDescriptions = &binding;
    vertex.vertexAttributeDescriptionCount = 2;
    vertex.pVertexAttributeDescriptions = attributes;
  }
  VkPipelineInputAssemblyStateCreateInfo assembly{};
  assembly.sType = VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO;
  assembly.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
  // Positive height: row 0 at the top, NDC y = -1 there; the projection itself flips y.
  const VkViewport viewport{0.0f, 0.0f, float(d.width), float(d.height), 0.0f, 1.0f};
  const VkRect2D scissor{{0, 0}, {d.width, d.height}};
  VkPipelineViewportStateCreateInfo view{};
  view.sType = VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO;
  view.viewportCount = 1;
  view.pViewports = &viewport;
  view.scissorCount = 1;
  view.pScissors = &scissor;
  VkPipelineRasterizationStateCreateInfo raster{};
  raster.sType = VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO;
  raster.polygonMode = VK_POLYGON_MODE_FILL;
  raster.cullMode = VK_CULL_MODE_NONE;
  raster.frontFace = VK_FRONT_FACE_CLOCKWISE;
  raster.lineWidth = 1.0f;
  VkPipelineMultisampleStateCreateInfo multisample{};
  multisample.sType = VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO;
  multisample.rasterizationSamples = d.samples;
  VkPipelineDepthStencilStateCreateInfo depth{};
  depth.sType = VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO;
  depth.depthTestEnable = d.depth ? VK_TRUE : VK_FALSE;
  depth.depthWriteEnable = d.depth ? VK_TRUE : VK_FALSE;
  depth.depthCompareOp = VK_COMPARE_OP_GREATER;  // reverse-Z: near is 1, nothing is 0
  std::vector<VkPipelineColorBlendAttachmentState> blends(d.colors);
  for (VkPipelineColorBlendAttachmentState& b : blends) {
    b = VkPipelineColorBlendAttachmentState{};
    b.colorWriteMask = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT | VK_COLOR_COMPONENT_B_BIT |
                       VK_COLOR_COMPONENT_A_BIT;
  }
  VkPipelineColorBlendStateCreateInfo blend{};
  blend.sType = VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO;
  blend.attachmentCount = d.colors;
  blend.pAttachments = blends.data();
  VkGraphicsPipelineCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO;
  info.stageCount = 2;
  info.pStages = stages;
  info.pVertexInputState = &vertex;
  info.pInputAssemblyState = &assembly;
  info.pViewportState = &view;
  info.pRasterizationState = &raster;
  info.pMultisampleState = &multisample;
  info.pDepthStencilState = &depth;
  info.pColorBlendState = &blend;
  info.layout = d.layout;
  info.renderPass = d.pass;
  info.subpass = d.subpass;
  VkPipeline p;
  TD_CHECK(vkCreateGraphicsPipelines(g.device, VK_NULL_HANDLE, 1, &info, nullptr, &p));
  return p;
}

VkPipeline make_compute_pipeline(const gpu& g, VkShaderModule module, VkPipelineLayout layout) {
  VkComputePipelineCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO;
  info.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
  info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
  info.stage.module = module;
  info.stage.pName = "main";
  info.layout = layout;
  VkPipeline p;
  TD_CHECK(vkCreateComputePipelines(g.device, VK_NULL_HANDLE, 1, &info, nullptr, &p));
  return p;
}

}  // namespace td
