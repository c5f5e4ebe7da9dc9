// Read-back of small windows of the frame's targets (the pixel probe): only the texels asked for
// cross to the host, through a small graph run after the frame (renderer.h: runAfterFrame).
#pragma once
#include <vector>

#include "renderer/frame/renderer.h"

namespace gb {

struct RegionRequest {
  Target target;
  int32_t x = 0, y = 0;  // target texel of the window's top-left corner (may lie outside)
  uint32_t width = 1, height = 1;
};

struct RegionImage {
  Target target = Target::Final;
  CpuImage image;  // empty when the window lies outside the target
  uint32_t x0 = 0, y0 = 0;  // target texel of image texel (0, 0): the window clamped to the target
  uint32_t targetWidth = 0, targetHeight = 0;
};

// Copies each window (clamped to its target) to the host. The targets must be readable (not
// transient); afterwards `handOff` targets are left readable by fragment shaders (the viewer's
// views sample them).
std::vector<RegionImage> readbackRegions(Renderer& r, const std::vector<RegionRequest>& requests,
                                         const std::vector<Target>& handOff);

}  // namespace gb
