// Pipelines and descriptors for the passes (the frame function's toolkit): cached graphics and
// compute pipelines, the common specialization constants, descriptor binding and depth tests.
#pragma once
#include <functional>
#include <initializer_list>
#include <string>
#include <vector>

#include "renderer/gpu/renderer_state.h"

namespace gb {

// Cached graphics pipeline for the current render pass / subpass; `fill` describes it once.
VkPipeline graphicsPipeline(Renderer& r, const PassContext& pc, const std::string& id,
                            const std::function<void(GraphicsPipelineDesc&)>& fill);
// Cached compute pipeline of r.pipelineLayout with the common specialization constants.
VkPipeline computePipeline(Renderer& r, Shader shader);
struct PassImage {
  uint32_t binding;
  VkDescriptorType type;
  VkImageView view;
  VkImageLayout layout;
  VkSampler sampler = VK_NULL_HANDLE;
};
// A storage buffer pushed to set 1 (clustered shading's buffers).
struct PassBuffer {
  uint32_t binding;
  VkBuffer buffer;
};
// Binds set 0 (scene) and pushes set 1 (this pass's images) for a pipeline of `layout`.
void bindDescriptors(Renderer& r, VkCommandBuffer cmd, VkPipelineLayout layout, std::initializer_list<PassImage> images,
                     VkPipelineBindPoint bindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS);
// Depth-test helpers that follow options.reversedZ.
VkCompareOp closerOrEqual(const Renderer& r);   // LESS_OR_EQUAL, or GREATER_OR_EQUAL reversed
VkCompareOp fartherOrEqual(const Renderer& r);  // the opposite
float farDepth(const Renderer& r);

// Specialization constants every pipeline gets (eye depth, reversed Z, normal encoding, ...).
std::vector<SpecConstant> commonSpec(const Renderer& r);

}  // namespace gb
