// The renderer built from a mode table (modes.h): per pass a VkRenderPass with one subpass, its images,
// framebuffer, descriptor set and pipelines; the shared buffers; recording one frame.
#pragma once
#include <vector>

#include "camera.h"
#include "gpu.h"
#include "modes.h"
#include "scene.h"

namespace zoo {

struct PassGpu {
  VkRenderPass render_pass = VK_NULL_HANDLE;
  VkFramebuffer framebuffer = VK_NULL_HANDLE;
  VkDescriptorSetLayout set_layout = VK_NULL_HANDLE;
  VkPipelineLayout layout = VK_NULL_HANDLE;
  VkDescriptorSet set = VK_NULL_HANDLE;
  std::vector<VkPipeline> pipelines;  // one per Draw
  std::vector<Image> images;          // one per Attachment
};

struct Renderer {
  const ModeDesc* desc = nullptr;
  uint32_t width = 0, height = 0;
  Geometry geometry;
  Buffer vertices, indices, camera, objects, lights;
  VkSampler sampler = VK_NULL_HANDLE;
  VkDescriptorPool pool = VK_NULL_HANDLE;
  std::vector<PassGpu> passes;
};

// True when a later pass of the mode samples attachment `a` of pass `p`.
bool sampled_later(const ModeDesc& m, int p, int a);
// The layout an attachment ends its render pass in.
VkImageLayout final_layout(const ModeDesc& m, int p, int a);

Renderer make_renderer(const Gpu& g, Mode mode, uint32_t width, uint32_t height);
// Host writes of the frame's camera block, objects and lights (before its submission).
void upload_frame(Renderer& r, const Camera& cam, uint32_t frame);
void record_frame(const Renderer& r, VkCommandBuffer cmd);
void free_renderer(const Gpu& g, Renderer& r);

// pipelines.cpp
VkPipeline make_pipeline(const Gpu& g, const Pass& pass, const Draw& draw, VkRenderPass rp, VkPipelineLayout layout);

}  // namespace zoo
