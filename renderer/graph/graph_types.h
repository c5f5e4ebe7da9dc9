// What passes declare to the frame graph (a Use: a target and how it is accessed), the state the
// graph tracks per target, and what a pass gets when it records (PassContext).
#pragma once
#include <vulkan/vulkan.h>

#include <array>
#include <cstdint>

#include "renderer/core/targets.h"
#include "renderer/vk/resources.h"

namespace gb {

enum class Access : uint8_t {
  ColorWrite,             // colour attachment, written
  ColorBlend,             // colour attachment, read-modify-write (blending)
  DepthStencilWrite,      // depth/stencil attachment, both written
  DepthTestStencilWrite,  // depth tested (not written), stencil written; depth may be read too
  DepthStencilRead,       // depth/stencil attachment, read only
  InputAttachment,        // subpass input (single-pass path)
  SampledFragment,        // texture read in a fragment shader
  SampledCompute,         // texture read in a compute shader
  StorageFragment,        // storage image read/written in a fragment shader (atomics)
  StorageCompute,         // storage image read/written in a compute shader
  TransferSrc,
  TransferDst,
};

struct Use {
  Target target;
  Access access;
  bool clear = false;  // first use in its render pass clears to clearValue
  VkClearValue clearValue{};
};

// A buffer a pass reads or writes (light lists, cluster data, indirect arguments): the graph
// places buffer barriers between its uses within a frame as it does image barriers. (Host
// writes before the submission need none; a buffer the CPU reads after the frame is declared
// HostRead by a pass at the end.)
enum class BufferAccess : uint8_t {
  TransferWrite,     // vkCmdFillBuffer / vkCmdUpdateBuffer / copy destination
  TransferRead,      // copy source
  ComputeRead,       // storage buffer read in a compute shader
  ComputeReadWrite,  // storage buffer written (atomics included) in a compute shader
  IndirectRead,      // indirect draw or dispatch arguments
  VertexRead,        // storage buffer read in a vertex shader
  FragmentRead,      // storage buffer read in a fragment shader
  HostRead,          // mapped and read by the CPU after the fence
};
struct BufferUse {
  VkBuffer buffer;
  BufferAccess access;
};
// What the graph tracks per buffer within a frame (like GraphTarget's stage/access).
struct GraphBufferState {
  VkPipelineStageFlags2 stage = VK_PIPELINE_STAGE_2_NONE;
  VkAccessFlags2 access = 0;
};

// A target as the graph sees it: its image and the state the last recorded use left it in.
struct GraphTarget {
  Image image;
  VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;
  VkPipelineStageFlags2 stage = VK_PIPELINE_STAGE_2_NONE;
  VkAccessFlags2 access = 0;
  bool keep = false;  // contents must survive past the frame (read-back, reuse next frame)
};
using GraphTargets = std::array<GraphTarget, kTargetCount>;

struct PassContext {
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  VkRenderPass renderPass = VK_NULL_HANDLE;  // null for compute/transfer passes
  uint32_t subpass = 0;
  uint32_t colorAttachments = 0;  // colour attachments of this subpass (pipelines need one blend state each)
  uint32_t compatClass = 0;       // render-pass compatibility class of this subpass (pipeline caches)
  VkExtent2D extent{};
  std::array<VkImageLayout, kTargetCount> layouts{};  // each target's layout during this pass
};

}  // namespace gb
