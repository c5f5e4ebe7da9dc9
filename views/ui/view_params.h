// The GPU parameters of a view: its mapping (views/analysis/visualize.h: the same choices the CPU
// mapping makes), range, placement, texel grid and marks. No ImGui and no Vulkan here: the choices
// are testable on their own.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "views/analysis/visualize.h"

namespace gb {

// Where an image lies in a view's rectangle: framebuffer position of texel (0,0)'s corner and
// framebuffer pixels per texel.
struct Placement {
  double originX = 0.0, originY = 0.0, scale = 1.0;
};

// Where the GPU reads a view's values: a decoded view image (captures: components in channels 0..3,
// empty texels marked), or gblens's live target, whose channels the quantity names.
struct ViewGpuSource {
  bool decoded = true;
  bool nativeNormal = false;          // live normal target: decoded with the frame's NORMAL_ENCODING
  std::vector<uint32_t> channelOf;    // component -> channel of the source (identity when decoded)
  std::optional<double> background;   // live: the stored value where nothing was drawn (kRangeNotValue)
};

// Push constants for drawing a view. `markTexel`: shadow-map texel whose screen samples are marked.
gpu::ViewParams viewParams(const ViewDef& def, const ViewSettings& s, const ViewGpuSource& src, const ResolvedRange& range,
                           const Placement& placement, bool grid, std::optional<glm::ivec2> markTexel,
                           glm::uvec2 shadowMapSize);

}  // namespace gb
