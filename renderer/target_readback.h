// Read-back of whole targets (target_readback.cpp): the copy recorded at the end of a frame and
// the texels unpacked into CpuImages.
#pragma once
#include "renderer/renderer.h"

namespace gb {

// Copies a target into its read-back buffer (after the graph has put it in TRANSFER_SRC).
void recordReadback(Renderer& r, VkCommandBuffer cmd, Target t);

// Decodes tightly packed texels as vkCmdCopyImageToBuffer wrote them (for depth/stencil: the
// depth aspect, then one stencil byte per texel) into a CpuImage of the target's description.
CpuImage unpackTexels(Target t, const RenderOptions& options, VkFormat format, const uint8_t* src, uint32_t width,
                      uint32_t height);
// The read-back buffer of `t` after the frame, unpacked.
CpuImage unpackReadback(Renderer& r, Target t);

}  // namespace gb
