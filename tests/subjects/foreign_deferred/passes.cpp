// foreign_deferred's targets, meshes and the recording of one frame (see passes.h).
#include "passes.h"

#include <cstring>

namespace fd {

namespace {

// The clear value of each target (the background where nothing is drawn): position w = 1 (the far
// plane in eye depth / far), depth 1 (standard depth), occlusion 1 (unoccluded).
VkClearValue clear_value(target_id t) {
  VkClearValue v{};
  switch (t) {
    case t_position: v.color = {{0.0f, 0.0f, 0.0f, 1.0f}}; break;
    case t_depth: v.depthStencil = {1.0f, 0}; break;
    case t_occlusion: v.color = {{1.0f, 0.0f, 0.0f, 0.0f}}; break;
    default: v.color = {{0.0f, 0.0f, 0.0f, 0.0f}}; break;
  }
  return v;
}

buffer_t upload(const device_t& d, const void* data, size_t bytes, VkBufferUsageFlags usage) {
  buffer_t b = create_host_buffer(d, bytes, usage);
  std::memcpy(b.mapped, data, bytes);
  return b;
}

void begin_pass(const renderer& r, VkCommandBuffer cmd, const screen_pass& p, std::initializer_list<target_id> targets) {
  std::vector<VkClearValue> clears;
  for (target_id t : targets) clears.push_back(clear_value(t));
  VkRenderPassBeginInfo begin{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
  begin.renderPass = p.render_pass;
  begin.framebuffer = p.framebuffer;
  begin.renderArea = {{0, 0}, {r.width, r.height}};
  begin.clearValueCount = uint32_t(clears.size());
  begin.pClearValues = clears.data();
  vkCmdBeginRenderPass(cmd, &begin, VK_SUBPASS_CONTENTS_INLINE);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, p.pipeline);
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, p.layout, 0, 1, &p.set, 0, nullptr);
}

void full_screen(const renderer& r, VkCommandBuffer cmd, const screen_pass& p, target_id target) {
  begin_pass(r, cmd, p, {target});
  vkCmdDraw(cmd, 3, 1, 0, 0);
  vkCmdEndRenderPass(cmd);
}

}  // namespace

const target_desc& describe(target_id t) {
  static const target_desc table[t_count] = {
      {"position.bin", VK_FORMAT_R32G32B32A32_SFLOAT, 16}, {"normal.bin", VK_FORMAT_R8G8B8A8_UNORM, 4},
      {"albedo.bin", VK_FORMAT_R8G8B8A8_SRGB, 4},          {"depth.bin", VK_FORMAT_D32_SFLOAT, 4},
      {"occlusion.bin", VK_FORMAT_R8_UNORM, 1},            {"hdr.bin", VK_FORMAT_R16G16B16A16_SFLOAT, 8},
      {"final.bin", VK_FORMAT_R8G8B8A8_UNORM, 4},
  };
  return table[t];
}

renderer create_renderer(const device_t& d, uint32_t width, uint32_t height, const scene& meshes_from) {
  renderer r;
  r.width = width;
  r.height = height;
  for (int t = 0; t < t_count; ++t) {
    const VkImageUsageFlags usage =
        t == t_depth ? VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT
                     : VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    r.targets[t] = create_image(d, describe(target_id(t)).format, width, height, usage);
  }
  r.uniforms = create_host_buffer(d, sizeof(frame_uniforms), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);
  for (const mesh& m : meshes_from.meshes) {
    gpu_mesh g;
    g.vertices = upload(d, m.vertices.data(), m.vertices.size() * sizeof(vertex), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
    g.indices = upload(d, m.indices.data(), m.indices.size() * sizeof(uint32_t), VK_BUFFER_USAGE_INDEX_BUFFER_BIT);
    g.index_count = uint32_t(m.indices.size());
    r.meshes.push_back(g);
  }
  VkSamplerCreateInfo sampler{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  sampler.magFilter = sampler.minFilter = VK_FILTER_NEAREST;
  sampler.addressModeU = sampler.addressModeV = sampler.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  FD_CHECK(vkCreateSampler(d.device, &sampler, nullptr, &r.sampler));
  const VkDescriptorPoolSize sizes[2] = {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 4},
                                         {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 8}};
  VkDescriptorPoolCreateInfo pool{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  pool.maxSets = 4;
  pool.poolSizeCount = 2;
  pool.pPoolSizes = sizes;
  FD_CHECK(vkCreateDescriptorPool(d.device, &pool, nullptr, &r.descriptor_pool));
  create_render_passes(d, r);
  create_pipelines(d, r);
  return r;
}

void destroy_renderer(const device_t& d, renderer& r) {
  for (screen_pass* p : {&r.geometry, &r.occlusion, &r.lighting, &r.present}) {
    vkDestroyPipeline(d.device, p->pipeline, nullptr);
    vkDestroyPipelineLayout(d.device, p->layout, nullptr);
    vkDestroyDescriptorSetLayout(d.device, p->set_layout, nullptr);
    vkDestroyFramebuffer(d.device, p->framebuffer, nullptr);
    vkDestroyRenderPass(d.device, p->render_pass, nullptr);
  }
  vkDestroyDescriptorPool(d.device, r.descriptor_pool, nullptr);
  vkDestroySampler(d.device, r.sampler, nullptr);
  for (gpu_mesh& m : r.meshes) {
    destroy_buffer(d, m.vertices);
    destroy_buffer(d, m.indices);
  }
  destroy_buffer(d, r.uniforms);
  for (image_t& i : r.targets) destroy_image(d, i);
  r = renderer{};
}

void record_frame(const renderer& r, VkCommandBuffer cmd, const scene& s) {
  begin_pass(r, cmd, r.geometry, {t_position, t_normal, t_albedo, t_depth});
  for (const draw& dr : s.draws) {
    const gpu_mesh& m = r.meshes[dr.mesh];
    struct {
      glm::mat4 world_from_object;
      glm::vec4 albedo;
    } push{dr.world_from_object, dr.albedo};
    vkCmdPushConstants(cmd, r.geometry.layout, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                       sizeof(push), &push);
    const VkDeviceSize offset = 0;
    vkCmdBindVertexBuffers(cmd, 0, 1, &m.vertices.buffer, &offset);
    vkCmdBindIndexBuffer(cmd, m.indices.buffer, 0, VK_INDEX_TYPE_UINT32);
    vkCmdDrawIndexed(cmd, m.index_count, 1, 0, 0, 0);
  }
  vkCmdEndRenderPass(cmd);
  full_screen(r, cmd, r.occlusion, t_occlusion);
  full_screen(r, cmd, r.lighting, t_hdr);
  full_screen(r, cmd, r.present, t_final);
}

}  // namespace fd
