// The pixels whose shadow lookup reads a shadow-map texel (the viewer's "marked" pixels), from a
// frame snapshot: how many, where they lie, and why there are none when there are none.
#pragma once
#include <glm/glm.hpp>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "renderer/core/snapshot.h"
#include "views/analysis/region_stats.h"

namespace gb {

struct ShadowMarks {
  int64_t pixels = 0;                    // pixels whose 2x2 lookup block holds the texel
  std::optional<RegionRect> box;         // their bounding box (frame pixels); none when none
  std::vector<glm::ivec2> some;          // up to kShadowMarksKept of them, row by row (drawn by the viewer)
  // Every lookup of the frame: how many pixels have one, and the shadow-map texels they read.
  int64_t lookups = 0;
  glm::ivec2 readMin{0}, readMax{-1};
  std::string note;                      // pixels == 0: why, in one sentence
};
inline constexpr size_t kShadowMarksKept = 4096;

// `texel`: a shadow-map texel (its x, y). The rule is the probe's (shadowMapFootprint): the texel
// is marked by a pixel whose bilinear 2x2 block [x0, x0 + 1] x [y0, y0 + 1] holds it.
ShadowMarks shadowMarks(const FrameSnapshot& frame, glm::ivec2 texel);

}  // namespace gb
