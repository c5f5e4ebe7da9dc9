// The viewer's views as data: which target each reads and how it maps it for people (normals as
// colour, depth near-bright over its automatic range, coverage as a heat map, ...), the user's
// per-view settings (channels, black/white point, highlights), and the GPU parameters that
// follow from them. No ImGui and no Vulkan here: the choices are testable on their own.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "views/analysis/view_table.h"
#include "views/ui/view_map.h"

namespace gb {

struct ViewSettings {
  uint32_t channels = 0xF;
  bool autoRange = false;
  float black = 0.0f, white = 1.0f;
  bool specials = true;  // NaN / Inf highlighted
  bool negative = true;  // negative highlighted (where the view calls them suspicious)
};
ViewSettings defaultSettings(ViewKind kind);

// The automatic range requests a view needs (one per selected channel), empty when manual.
std::vector<RangeRequest> rangeRequests(const ViewDef& def, const ViewSettings& s);

// The range a view maps, from the data (auto) or the settings; `stats` are the results of
// rangeRequests() in order (null: not computed yet).
struct ResolvedRange {
  float black = 0.0f, white = 1.0f;
  bool fromData = false;  // auto and there was valid data
  RangeStats stats;       // combined over the selected channels (auto only)
};
ResolvedRange resolveRange(const ViewDef& def, const ViewSettings& s, const std::vector<RangeStats>* stats);

// Where an image lies in a view's rectangle: framebuffer position of texel (0,0)'s corner and
// framebuffer pixels per texel.
struct Placement {
  double originX = 0.0, originY = 0.0, scale = 1.0;
};

// Push constants for drawing a view. `markTexel`: shadow-map texel whose screen samples are marked.
gpu::ViewParams viewParams(const ViewDef& def, const ViewSettings& s, const ResolvedRange& range, const Placement& placement,
                           bool grid, std::optional<glm::ivec2> markTexel, glm::uvec2 shadowMapSize);

}  // namespace gb
