// Shader modules from the embedded variants (shader_ids.h) and a plain-struct description of a graphics or
// compute pipeline. Pipelines use dynamic viewport/scissor, cull mode and front face.
#pragma once
#include <vulkan/vulkan.h>

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "renderer/vk/context.h"
#include "shader_ids.h"  // generated from shaders/shaders.cmake: enum class Shader

namespace gb {

VkShaderModule createShaderModule(GpuContext& ctx, Shader shader);

struct SpecConstant {
  uint32_t id;
  uint32_t value;
};

enum class VertexInput { None, SceneVertex, Position };  // Position: a bare vec3 stream (light volumes)

struct BlendState {
  bool enable = false;
  VkBlendFactor src = VK_BLEND_FACTOR_ONE, dst = VK_BLEND_FACTOR_ONE;
  VkBlendFactor srcAlpha = VK_BLEND_FACTOR_ONE, dstAlpha = VK_BLEND_FACTOR_ONE;
  VkColorComponentFlags writeMask = 0xF;
};

struct GraphicsPipelineDesc {
  Shader vertexShader = Shader::None;
  Shader fragmentShader = Shader::None;  // None: no fragment stage (depth/stencil only)
  std::vector<SpecConstant> spec;
  VertexInput vertexInput = VertexInput::None;
  uint32_t vertexAttributes = 0x1F;  // SceneVertex: bit i = location i is read by the vertex shader
  bool depthTest = false, depthWrite = false;
  VkCompareOp depthCompare = VK_COMPARE_OP_LESS_OR_EQUAL;
  bool depthClamp = false;
  bool depthBias = false;  // values are dynamic state
  bool stencilTest = false;
  VkStencilOpState stencil{};  // front faces (and back faces unless separateBackStencil)
  bool separateBackStencil = false;
  VkStencilOpState stencilBack{};
  bool dynamicStencilMasks = false;  // compare/write masks set per draw (per-light stencil bits)
  std::vector<BlendState> colorBlend;  // one per colour attachment of the subpass
  bool rasterOrderColor = false;       // VK_EXT_rasterization_order_attachment_access
  VkRenderPass renderPass = VK_NULL_HANDLE;
  uint32_t subpass = 0;
  VkPipelineLayout layout = VK_NULL_HANDLE;
  std::string name;  // the pipeline's debug name (RenderDoc): the pass's pipeline id
};

// The values of specialization constants, in order (cache keys).
std::vector<uint32_t> specValues(std::span<const SpecConstant> spec);

VkPipeline createGraphicsPipeline(GpuContext& ctx, const GraphicsPipelineDesc& desc);
VkPipeline createComputePipeline(GpuContext& ctx, Shader shader, std::span<const SpecConstant> spec,
                                 VkPipelineLayout layout);
// A descriptor set layout of these bindings (flags: push descriptors, say), named for RenderDoc.
VkDescriptorSetLayout createSetLayout(GpuContext& ctx, const std::vector<VkDescriptorSetLayoutBinding>& bindings,
                                      VkDescriptorSetLayoutCreateFlags flags, const char* name);

}  // namespace gb
