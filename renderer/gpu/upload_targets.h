// Targets from CPU images (a capture opened in the viewer): each image is packed back into its
// target's format, uploaded, and left readable by shaders, so every view, range and region
// read-back works on a capture exactly as on a live frame.
#pragma once
#include <array>

#include "renderer/gpu/renderer_state.h"

namespace gb {

// Replaces r's targets with uploads of `images` (null: the target stays empty) for `options`
// (formats, size). The renderer renders nothing afterwards: it only holds the frame.
void uploadTargets(Renderer& r, const RenderOptions& options, const std::array<const CpuImage*, kTargetCount>& images);

}  // namespace gb
