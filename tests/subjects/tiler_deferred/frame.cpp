// tiler_deferred: what both modes share (frame.h): mesh and uniform buffers, set 0, the geometry pipeline
// layout, the draw loop, and small render-pass helpers.
#include "frame.h"

#include <cstring>

#include "fullscreen_vert.h"
#include "geometry_vert.h"

namespace td {

shared_gpu make_shared(const gpu& g, const scene& s) {
  shared_gpu sh;
  const size_t vbytes = s.vertices.size() * sizeof(vertex), ibytes = s.indices.size() * sizeof(uint32_t);
  sh.vertices = make_buffer(g, vbytes, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
  std::memcpy(sh.vertices.mapped, s.vertices.data(), vbytes);
  sh.indices = make_buffer(g, ibytes, VK_BUFFER_USAGE_INDEX_BUFFER_BIT);
  std::memcpy(sh.indices.mapped, s.indices.data(), ibytes);
  const uint32_t align = uint32_t(g.limits.minUniformBufferOffsetAlignment);
  sh.slot_bytes = 512;
  while (sh.slot_bytes % align) sh.slot_bytes += 512;
  sh.uniforms = make_buffer(g, 2 * sh.slot_bytes, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);
  sh.frame_layout = make_set_layout(g, {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER_DYNAMIC},
                                    VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT);
  // Room for every mode's sets: set 0, the lighting set (4 images), the dump compute set (4 + 1), the
  // compute mode's resolve set (2 sampled + 2 storage images).
  const VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER_DYNAMIC, 1},
                                        {VK_DESCRIPTOR_TYPE_INPUT_ATTACHMENT, 4},
                                        {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 8},
                                        {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1},
                                        {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 2}};
  VkDescriptorPoolCreateInfo pool{};
  pool.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO;
  pool.maxSets = 4;
  pool.poolSizeCount = 5;
  pool.pPoolSizes = sizes;
  TD_CHECK(vkCreateDescriptorPool(g.device, &pool, nullptr, &sh.pool));
  VkDescriptorSetAllocateInfo alloc{};
  alloc.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO;
  alloc.descriptorPool = sh.pool;
  alloc.descriptorSetCount = 1;
  alloc.pSetLayouts = &sh.frame_layout;
  TD_CHECK(vkAllocateDescriptorSets(g.device, &alloc, &sh.frame_set));
  const VkDescriptorBufferInfo range{sh.uniforms.handle, 0, sizeof(frame_block)};
  VkWriteDescriptorSet write{};
  write.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
  write.dstSet = sh.frame_set;
  write.descriptorCount = 1;
  write.descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER_DYNAMIC;
  write.pBufferInfo = &range;
  vkUpdateDescriptorSets(g.device, 1, &write, 0, nullptr);
  sh.geometry_layout = make_pipeline_layout(g, {sh.frame_layout}, sizeof(object_push),
                                            VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT);
  sh.geometry_vert = make_shader(g, td_geometry_vert, sizeof(td_geometry_vert));
  sh.fullscreen_vert = make_shader(g, td_fullscreen_vert, sizeof(td_fullscreen_vert));
  return sh;
}

void drop_shared(const gpu& g, shared_gpu& sh) {
  vkDestroyShaderModule(g.device, sh.geometry_vert, nullptr);
  vkDestroyShaderModule(g.device, sh.fullscreen_vert, nullptr);
  vkDestroyPipelineLayout(g.device, sh.geometry_layout, nullptr);
  vkDestroyDescriptorPool(g.device, sh.pool, nullptr);
  vkDestroyDescriptorSetLayout(g.device, sh.frame_layout, nullptr);
  drop_buffer(g, sh.vertices);
  drop_buffer(g, sh.indices);
  drop_buffer(g, sh.uniforms);
  sh = shared_gpu{};
}

void bind_frame_set(VkCommandBuffer cmd, VkPipelineLayout layout, const shared_gpu& sh, const frame_input& in) {
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout, 0, 1, &sh.frame_set, 1, &in.uniform_offset);
}

void draw_objects(VkCommandBuffer cmd, const shared_gpu& sh, VkPipeline pipeline, const frame_input& in) {
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline);
  bind_frame_set(cmd, sh.geometry_layout, sh, in);
  const VkDeviceSize zero = 0;
  vkCmdBindVertexBuffers(cmd, 0, 1, &sh.vertices.handle, &zero);
  vkCmdBindIndexBuffer(cmd, sh.indices.handle, 0, VK_INDEX_TYPE_UINT32);
  for (const object& o : in.objects->objects) {
    const object_push p = build_push(o);
    vkCmdPushConstants(cmd, sh.geometry_layout, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                       sizeof(p), &p);
    vkCmdDrawIndexed(cmd, o.mesh.index_count, 1, o.mesh.first_index, o.mesh.vertex_offset, 0);
  }
}

VkImageMemoryBarrier image_barrier(const image& i, VkAccessFlags src, VkAccessFlags dst, VkImageLayout from,
                                   VkImageLayout to) {
  VkImageMemoryBarrier b{};
  b.sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER;
  b.srcAccessMask = src;
  b.dstAccessMask = dst;
  b.oldLayout = from;
  b.newLayout = to;
  b.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.image = i.handle;
  b.subresourceRange = {i.aspect, 0, 1, 0, 1};
  return b;
}

VkAttachmentDescription attachment(VkFormat format, VkSampleCountFlagBits samples, VkAttachmentLoadOp load,
                                   VkAttachmentStoreOp store, VkImageLayout final_layout) {
  VkAttachmentDescription a{};
  a.format = format;
  a.samples = samples;
  a.loadOp = load;
  a.storeOp = store;
  a.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
  a.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
  a.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;  // every frame starts afresh
  a.finalLayout = final_layout;
  return a;
}

VkFramebuffer make_framebuffer(const gpu& g, VkRenderPass pass, const std::vector<VkImageView>& views,
                               uint32_t width, uint32_t height) {
  VkFramebufferCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO;
  info.renderPass = pass;
  info.attachmentCount = uint32_t(views.size());
  info.pAttachments = views.data();
  info.width = width;
  info.height = height;
  info.layers = 1;
  VkFramebuffer f;
  TD_CHECK(vkCreateFramebuffer(g.device, &info, nullptr, &f));
  return f;
}

VkDescriptorSet allocate_set(const gpu& g, VkDescriptorPool pool, VkDescriptorSetLayout layout) {
  VkDescriptorSetAllocateInfo alloc{};
  alloc.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO;
  alloc.descriptorPool = pool;
  alloc.descriptorSetCount = 1;
  alloc.pSetLayouts = &layout;
  VkDescriptorSet set;
  TD_CHECK(vkAllocateDescriptorSets(g.device, &alloc, &set));
  return set;
}

VkRenderPass make_pass(const gpu& g, const std::vector<VkAttachmentDescription>& attachments,
                       const VkSubpassDescription& subpass, const std::vector<VkSubpassDependency>& deps) {
  VkRenderPassCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO;
  info.attachmentCount = uint32_t(attachments.size());
  info.pAttachments = attachments.data();
  info.subpassCount = 1;
  info.pSubpasses = &subpass;
  info.dependencyCount = uint32_t(deps.size());
  info.pDependencies = deps.data();
  VkRenderPass pass;
  TD_CHECK(vkCreateRenderPass(g.device, &info, nullptr, &pass));
  return pass;
}

VkRenderPass make_lit_pass(const gpu& g) {
  const VkAttachmentReference lit{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
  VkSubpassDescription sub{};
  sub.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
  sub.colorAttachmentCount = 1;
  sub.pColorAttachments = &lit;
  const VkPipelineStageFlags out = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
  return make_pass(g,
                   {attachment(VK_FORMAT_R16G16B16A16_SFLOAT, VK_SAMPLE_COUNT_1_BIT, VK_ATTACHMENT_LOAD_OP_DONT_CARE,
                               VK_ATTACHMENT_STORE_OP_STORE, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL)},
                   sub,
                   {{VK_SUBPASS_EXTERNAL, 0, out | VK_PIPELINE_STAGE_TRANSFER_BIT, out, VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT,
                     VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT, 0},
                    {0, VK_SUBPASS_EXTERNAL, out, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT,
                     VK_ACCESS_TRANSFER_READ_BIT, 0}});
}

target_info lit_target() {
  target_info lit;
  lit.name = "lit";
  lit.vk_format = "VK_FORMAT_R16G16B16A16_SFLOAT";
  lit.bytes_per_texel = 8;
  lit.render_pass = 1;
  lit.color = 0;
  lit.files = {"lit.bin"};
  return lit;
}

void draw_lit(VkCommandBuffer cmd, VkRenderPass pass, VkFramebuffer framebuffer, VkPipeline pipeline, VkPipelineLayout layout,
              VkDescriptorSet images, const shared_gpu& sh, const frame_input& in, uint32_t width, uint32_t height) {
  VkRenderPassBeginInfo begin{};
  begin.sType = VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO;
  begin.renderPass = pass;
  begin.framebuffer = framebuffer;
  begin.renderArea = {{0, 0}, {width, height}};
  vkCmdBeginRenderPass(cmd, &begin, VK_SUBPASS_CONTENTS_INLINE);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline);
  bind_frame_set(cmd, layout, sh, in);
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout, 1, 1, &images, 0, nullptr);
  vkCmdDraw(cmd, 3, 1, 0, 0);
  vkCmdEndRenderPass(cmd);
}

VkSampler make_nearest_sampler(const gpu& g) {
  VkSamplerCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO;
  info.magFilter = info.minFilter = VK_FILTER_NEAREST;
  info.addressModeU = info.addressModeV = info.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  VkSampler sampler = VK_NULL_HANDLE;
  TD_CHECK(vkCreateSampler(g.device, &info, nullptr, &sampler));
  return sampler;
}

}  // namespace td
