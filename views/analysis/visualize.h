// A view's values and their picture: each quantity decoded as its kind says (view_table.h), in the
// layout's own units and space, and mapped for people as the viewer's GPU mapping does
// (shaders/view_map.frag, colour maps from shaders/view_colors.h): colour sRGB-encoded after an
// exposure, normals as colour, depths near-bright or in false colour, ids and stencil values a colour
// each, motion on a colour wheel, counts as a heat map. `render --target`, capture previews, the
// viewer's capture views and their hover all read the values here.
#pragma once
#include <array>
#include <optional>

#include "renderer/core/snapshot.h"
#include "views/analysis/view_table.h"
#include "views/capture/image_io.h"

namespace gb {

// A viewer's per-view settings (the defaults come from the view table).
struct ViewSettings {
  uint32_t channels = 0xF;   // components shown (bit c = component c)
  bool autoRange = false;    // black and white point from the data
  float black = 0.0f, white = 1.0f;
  bool specials = true;      // NaN / Inf highlighted
  bool negative = true;      // negative highlighted (where the view calls them suspicious)
  float exposure = 0.0f;     // colour views: multiplied by 2^exposure before display
  bool log = false;          // grey and depth mappings: logarithmic between black and white
  bool falseColor = false;   // grey and depth mappings: viridis instead of grey
  uint32_t stencilBits = 0;  // stencil views: only these bits (0: the whole value)
  bool distance = false;     // position views: the distance to the eye instead of xyz
};
ViewSettings defaultSettings(const ViewDef& view);

// The value a view maps at target texel (x, y): colours linear (RGBA), normals unit in their own
// space with |stored| in [3], depths as the quantity stores them (hardware: the stored value; eye and
// radial: scaled), positions in their own space with the distance to the eye in [3], scalars and
// vectors scaled, integers, motion in pixels. Nothing where the frame does not hold the texel, and for
// normals, positions and camera depths where no surface was drawn.
std::optional<std::array<double, 4>> viewValue(const FrameSnapshot& f, const ViewDef& view, uint32_t x, uint32_t y);

// The whole view decoded (what the viewer uploads for a capture): RGBA32F, or R32_UINT for integer
// views, of the target's size; texels without a value hold gpu::kEmptyTexel in every channel, decoded
// NaNs are stored as one quiet NaN. Empty when the frame does not hold the target.
CpuImage viewImage(const FrameSnapshot& f, const ViewDef& view);
// A decoded view image of this size in viewImage's format, zero-filled: RGBA32F in channels "0".."3",
// or one R32_UINT channel named `name` for an integer view (the viewer's own maps use it too).
CpuImage decodedViewImage(const std::string& name, uint32_t width, uint32_t height, bool integer = false);

// How settings turn a view into the shader's mapping (gpu::kViewMap*), component mask and flags.
struct ViewMapping {
  uint32_t mapping = 0, mask = 0x7, flags = 0;
};
ViewMapping viewMapping(const ViewDef& view, const ViewSettings& s);

// Range statistics of values (the viewer's automatic ranges; GPU-reduced for live frames).
struct RangeStats {
  uint64_t count = 0, nan = 0, inf = 0, negative = 0;  // count: valid finite values
  double lo = 0.0, hi = 0.0;                            // meaningful when count > 0
};
// Of a decoded view image's components `mask` (empty texels left out; motion: the vectors' lengths).
RangeStats imageRange(const CpuImage& decoded, const ViewDef& view, uint32_t mask);

// The black and white point a view maps: the settings', or from the data (auto).
struct ResolvedRange {
  float black = 0.0f, white = 1.0f;
  bool fromData = false;  // auto and there was valid data
  RangeStats stats;       // combined over the selected components (auto only)
};
ResolvedRange resolveRange(const ViewDef& view, const ViewSettings& s, const std::vector<RangeStats>* stats);

// One texel's display colour (linear 0..1, before the sRGB encoding of the output), as the shader
// computes it; `v` holds the decoded components.
glm::vec3 mapTexel(const ViewDef& view, const ViewSettings& s, const ViewMapping& m, const ResolvedRange& r,
                   const std::array<float, 4>& v, bool empty);

// The view of a frame as an sRGB image, the range from the data where the settings say auto; an empty
// image when the frame does not hold the view's target.
Rgba8Image visualize(const FrameSnapshot& f, const ViewDef& view, const ViewSettings& s);

// Heat-map colour for a count (0 = black, then blue -> green -> yellow -> red at `max`), 8-bit.
void heatColor(double count, double max, uint8_t out[3]);

}  // namespace gb
