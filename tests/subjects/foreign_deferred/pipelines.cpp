// The render passes, framebuffers, descriptor sets and pipelines of foreign_deferred's four passes
// (see passes.h). Every pass clears its targets; nothing is named.
#include <cstdint>

#include "passes.h"
// SPIR-V from glslangValidator --vn (CMakeLists.txt): arrays of uint32_t.
#include "geometry_frag.h"
#include "geometry_vert.h"
#include "lighting_frag.h"
#include "occlusion_frag.h"
#include "present_frag.h"
#include "screen_vert.h"

namespace fd {

namespace {

// One dependency for both ends of every pass: whatever earlier passes (or the previous frame and
// its read-back) wrote or read happens before this pass, and this pass's writes before the next reader.
VkSubpassDependency external(bool into) {
  const VkPipelineStageFlags stages = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT |
                                      VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT |
                                      VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT;
  VkSubpassDependency dep{};
  dep.srcSubpass = into ? VK_SUBPASS_EXTERNAL : 0;
  dep.dstSubpass = into ? 0 : VK_SUBPASS_EXTERNAL;
  // The transfer stage (the dump's copies) only on the outside of the pass.
  dep.srcStageMask = stages | (into ? VK_PIPELINE_STAGE_TRANSFER_BIT : 0);
  dep.dstStageMask = stages | (into ? 0 : VK_PIPELINE_STAGE_TRANSFER_BIT);
  dep.srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
  dep.dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT |
                      VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT |
                      VK_ACCESS_SHADER_READ_BIT | (into ? 0 : VK_ACCESS_TRANSFER_READ_BIT);
  return dep;
}

// One attachment: cleared at the start, stored, left in `final_layout` for the passes after.
VkAttachmentDescription attachment(VkFormat format, VkImageLayout final_layout) {
  VkAttachmentDescription a{};
  a.format = format;
  a.samples = VK_SAMPLE_COUNT_1_BIT;
  a.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
  a.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  a.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
  a.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
  a.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  a.finalLayout = final_layout;
  return a;
}

// A render pass writing `colors` (left sampled-ready) and optionally a depth attachment, and its framebuffer.
void make_pass(const device_t& d, renderer& r, screen_pass& p, std::initializer_list<target_id> colors, bool depth) {
  std::vector<VkAttachmentDescription> attachments;
  std::vector<VkAttachmentReference> color_refs;
  std::vector<VkImageView> views;
  for (target_id t : colors) {
    color_refs.push_back({uint32_t(attachments.size()), VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL});
    attachments.push_back(attachment(describe(t).format, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL));
    views.push_back(r.targets[t].view);
  }
  VkAttachmentReference depth_ref{uint32_t(attachments.size()), VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
  if (depth) {
    attachments.push_back(attachment(describe(t_depth).format, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL));
    views.push_back(r.targets[t_depth].view);
  }
  VkSubpassDescription subpass{};
  subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
  subpass.colorAttachmentCount = uint32_t(color_refs.size());
  subpass.pColorAttachments = color_refs.data();
  subpass.pDepthStencilAttachment = depth ? &depth_ref : nullptr;
  const VkSubpassDependency deps[2] = {external(true), external(false)};
  VkRenderPassCreateInfo info{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
  info.attachmentCount = uint32_t(attachments.size());
  info.pAttachments = attachments.data();
  info.subpassCount = 1;
  info.pSubpasses = &subpass;
  info.dependencyCount = 2;
  info.pDependencies = deps;
  FD_CHECK(vkCreateRenderPass(d.device, &info, nullptr, &p.render_pass));
  VkFramebufferCreateInfo fb{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
  fb.renderPass = p.render_pass;
  fb.attachmentCount = uint32_t(views.size());
  fb.pAttachments = views.data();
  fb.width = r.width;
  fb.height = r.height;
  fb.layers = 1;
  FD_CHECK(vkCreateFramebuffer(d.device, &fb, nullptr, &p.framebuffer));
}

// Set 0: binding 0 the uniform buffer, bindings 1.. the targets the pass reads (nearest sampler).
void make_set(const device_t& d, renderer& r, screen_pass& p, std::initializer_list<target_id> reads) {
  std::vector<VkDescriptorSetLayoutBinding> bindings;
  bindings.push_back({0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, nullptr});
  for (size_t i = 0; i < reads.size(); ++i)
    bindings.push_back({uint32_t(i + 1), VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_FRAGMENT_BIT, nullptr});
  VkDescriptorSetLayoutCreateInfo info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  info.bindingCount = uint32_t(bindings.size());
  info.pBindings = bindings.data();
  FD_CHECK(vkCreateDescriptorSetLayout(d.device, &info, nullptr, &p.set_layout));
  VkDescriptorSetAllocateInfo alloc{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  alloc.descriptorPool = r.descriptor_pool;
  alloc.descriptorSetCount = 1;
  alloc.pSetLayouts = &p.set_layout;
  FD_CHECK(vkAllocateDescriptorSets(d.device, &alloc, &p.set));
  VkDescriptorBufferInfo ubo{r.uniforms.buffer, 0, sizeof(frame_uniforms)};
  std::vector<VkDescriptorImageInfo> images;
  for (target_id t : reads) images.push_back({r.sampler, r.targets[t].view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL});
  std::vector<VkWriteDescriptorSet> writes;
  VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
  w.dstSet = p.set;
  w.descriptorCount = 1;
  w.descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
  w.pBufferInfo = &ubo;
  writes.push_back(w);
  for (size_t i = 0; i < images.size(); ++i) {
    w.dstBinding = uint32_t(i + 1);
    w.descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    w.pBufferInfo = nullptr;
    w.pImageInfo = &images[i];
    writes.push_back(w);
  }
  vkUpdateDescriptorSets(d.device, uint32_t(writes.size()), writes.data(), 0, nullptr);
}

template <size_t N>
VkShaderModule shader(const device_t& d, const uint32_t (&code)[N]) {
  return create_shader(d, code, sizeof(code));
}

// A pipeline for pass p: `attachments` colour targets, the geometry pass's vertex layout and depth test when `mesh`.
void make_pipeline(const device_t& d, const renderer& r, screen_pass& p, VkShaderModule vs, VkShaderModule fs,
                   uint32_t attachments, bool mesh) {
  VkPushConstantRange push{VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(glm::mat4) + sizeof(glm::vec4)};
  VkPipelineLayoutCreateInfo layout{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  layout.setLayoutCount = 1;
  layout.pSetLayouts = &p.set_layout;
  layout.pushConstantRangeCount = mesh ? 1 : 0;
  layout.pPushConstantRanges = &push;
  FD_CHECK(vkCreatePipelineLayout(d.device, &layout, nullptr, &p.layout));

  VkPipelineShaderStageCreateInfo stages[2] = {{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO},
                                               {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO}};
  stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
  stages[0].module = vs;
  stages[0].pName = "main";
  stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
  stages[1].module = fs;
  stages[1].pName = "main";
  VkVertexInputBindingDescription binding{0, sizeof(vertex), VK_VERTEX_INPUT_RATE_VERTEX};
  VkVertexInputAttributeDescription attributes[2] = {{0, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(vertex, position)},
                                                     {1, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(vertex, normal)}};
  VkPipelineVertexInputStateCreateInfo input{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
  if (mesh) {
    input.vertexBindingDescriptionCount = 1;
    input.pVertexBindingDescriptions = &binding;
    input.vertexAttributeDescriptionCount = 2;
    input.pVertexAttributeDescriptions = attributes;
  }
  VkPipelineInputAssemblyStateCreateInfo assembly{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
  assembly.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
  VkViewport viewport{0, 0, float(r.width), float(r.height), 0, 1};
  VkRect2D scissor{{0, 0}, {r.width, r.height}};
  VkPipelineViewportStateCreateInfo vp{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
  vp.viewportCount = 1;
  vp.pViewports = &viewport;
  vp.scissorCount = 1;
  vp.pScissors = &scissor;
  VkPipelineRasterizationStateCreateInfo raster{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
  raster.polygonMode = VK_POLYGON_MODE_FILL;
  raster.cullMode = VK_CULL_MODE_NONE;  // closed meshes and a ground seen from above: the depth test decides
  raster.lineWidth = 1.0f;
  VkPipelineMultisampleStateCreateInfo ms{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
  ms.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
  VkPipelineDepthStencilStateCreateInfo ds{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
  ds.depthTestEnable = mesh;
  ds.depthWriteEnable = mesh;
  ds.depthCompareOp = VK_COMPARE_OP_LESS;
  std::vector<VkPipelineColorBlendAttachmentState> blend(attachments);
  for (auto& b : blend) b.colorWriteMask = 0xF;
  VkPipelineColorBlendStateCreateInfo cb{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
  cb.attachmentCount = attachments;
  cb.pAttachments = blend.data();
  VkGraphicsPipelineCreateInfo info{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
  info.stageCount = 2;
  info.pStages = stages;
  info.pVertexInputState = &input;
  info.pInputAssemblyState = &assembly;
  info.pViewportState = &vp;
  info.pRasterizationState = &raster;
  info.pMultisampleState = &ms;
  info.pDepthStencilState = &ds;
  info.pColorBlendState = &cb;
  info.layout = p.layout;
  info.renderPass = p.render_pass;
  FD_CHECK(vkCreateGraphicsPipelines(d.device, VK_NULL_HANDLE, 1, &info, nullptr, &p.pipeline));
  vkDestroyShaderModule(d.device, fs, nullptr);
}

}  // namespace

void create_render_passes(const device_t& d, renderer& r) {
  make_pass(d, r, r.geometry, {t_position, t_normal, t_albedo}, true);
  make_pass(d, r, r.occlusion, {t_occlusion}, false);
  make_pass(d, r, r.lighting, {t_hdr}, false);
  make_pass(d, r, r.present, {t_final}, false);
}

void create_pipelines(const device_t& d, renderer& r) {
  make_set(d, r, r.geometry, {});
  make_set(d, r, r.occlusion, {t_position, t_normal});
  make_set(d, r, r.lighting, {t_position, t_normal, t_albedo, t_occlusion});
  make_set(d, r, r.present, {t_hdr});
  const VkShaderModule geometry_vs = shader(d, fd_geometry_vert), screen_vs = shader(d, fd_screen_vert);
  make_pipeline(d, r, r.geometry, geometry_vs, shader(d, fd_geometry_frag), 3, true);
  make_pipeline(d, r, r.occlusion, screen_vs, shader(d, fd_occlusion_frag), 1, false);
  make_pipeline(d, r, r.lighting, screen_vs, shader(d, fd_lighting_frag), 1, false);
  make_pipeline(d, r, r.present, screen_vs, shader(d, fd_present_frag), 1, false);
  vkDestroyShaderModule(d.device, geometry_vs, nullptr);
  vkDestroyShaderModule(d.device, screen_vs, nullptr);
}

}  // namespace fd
