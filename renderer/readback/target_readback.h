// Read-back of whole targets (target_readback.cpp): the copy recorded at the end of a frame and
// the texels unpacked into CpuImages.
#pragma once
#include "renderer/gpu/renderer_state.h"

namespace gb {

// Copies a target into its read-back buffer (after the graph has put it in TRANSFER_SRC).
void recordReadback(Renderer& r, VkCommandBuffer cmd, Target t);

// The packed texels of target `t` (renderer/core/texels.h) as a CpuImage named and described as
// the target table says.
CpuImage unpackTarget(Target t, const RenderOptions& options, const uint8_t* src, uint32_t width, uint32_t height);
// The read-back buffer of `t` after the frame, unpacked.
CpuImage unpackReadback(Renderer& r, Target t);

}  // namespace gb
