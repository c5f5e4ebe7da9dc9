// foreign_deferred's frame: four render passes in this order, each its own VkRenderPass, no names:
//   1 geometry  -> position (rgba32f), normal (rgba8 unorm), albedo (rgba8 sRGB), depth (D32_SFLOAT)
//   2 occlusion -> occlusion (r8 unorm), reading position and normal
//   3 lighting  -> hdr (rgba16f), reading position, normal, albedo, occlusion
//   4 present   -> final (rgba8 unorm holding sRGB-encoded bytes), reading hdr
#pragma once
#include <vector>

#include "device.h"
#include "scene.h"

namespace fd {

// The targets in the order the render passes create and attach them.
enum target_id { t_position, t_normal, t_albedo, t_depth, t_occlusion, t_hdr, t_final, t_count };

struct target_desc {
  const char* file;         // the dump's file name (dump.cpp), never given to Vulkan
  VkFormat format;
  uint32_t bytes_per_texel;
};
const target_desc& describe(target_id t);

struct gpu_mesh {
  buffer_t vertices, indices;
  uint32_t index_count = 0;
};

struct screen_pass {
  VkRenderPass render_pass = VK_NULL_HANDLE;
  VkFramebuffer framebuffer = VK_NULL_HANDLE;
  VkDescriptorSetLayout set_layout = VK_NULL_HANDLE;
  VkDescriptorSet set = VK_NULL_HANDLE;
  VkPipelineLayout layout = VK_NULL_HANDLE;
  VkPipeline pipeline = VK_NULL_HANDLE;
};

struct renderer {
  uint32_t width = 0, height = 0;
  image_t targets[t_count];
  buffer_t uniforms;
  std::vector<gpu_mesh> meshes;
  VkSampler sampler = VK_NULL_HANDLE;
  VkDescriptorPool descriptor_pool = VK_NULL_HANDLE;
  screen_pass geometry, occlusion, lighting, present;  // geometry's pipeline draws meshes
};

renderer create_renderer(const device_t& d, uint32_t width, uint32_t height, const scene& meshes_from);
void destroy_renderer(const device_t& d, renderer& r);
// Records one frame: the uniforms must already be in r.uniforms.
void record_frame(const renderer& r, VkCommandBuffer cmd, const scene& s);

// pipelines.cpp: the render passes and pipelines (called by create_renderer).
void create_render_passes(const device_t& d, renderer& r);
void create_pipelines(const device_t& d, renderer& r);

}  // namespace fd
