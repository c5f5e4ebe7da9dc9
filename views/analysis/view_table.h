// The views of a frame, generated from its layout: one view per quantity the layout declares, with the
// visualisation its kind calls for. Nothing else: a quantity the layout lacks has no view, so no view
// ever shows a stand-in. The CPU mapping (visualize.h), the viewer (views/ui) and `render --target`
// all read this list; a view's name is its quantity's name (docs/analysis.md, "Views").
#pragma once
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "renderer/core/layout.h"
#include "shaders/shared.h"

namespace gb {

// How a quantity's decoded values become a picture (one per quantity kind family).
enum class Visual : uint8_t { Color, Normal, Depth, Position, Scalar, Vector, Id, Stencil, Motion, Count };
const char* name(Visual v);

struct ViewDef {
  std::string name;         // the quantity's name ("Albedo", "Combined"): --target, --view, keys, JSON
  int quantity = -1;        // index into the layout's quantities
  QuantityKind kind = QuantityKind::Scalar;
  Visual visual = Visual::Scalar;
  uint32_t target = 0;      // the layout target holding it
  uint32_t components = 1;  // of the decoded value (viewValue): colour 3-4, normal 3 (+ |stored|), ...
  std::vector<std::string> componentNames;  // "R", "G", "B" / "X", "Y", "Z" / the quantity's name
  std::string space;        // what its vectors or depths are: "view", "world (layout: Z-up)", "eye depth", ...
  std::string unit;         // of the mapped values, for the legend ("", "m", "shader runs")
  bool sun = false;         // the sun's depth (a shadow map): its own size and texel grid
  bool hdr = false;         // linear light that may exceed 1 (radiance, emission): exposure applies
  bool integer = false;     // id, stencil, count: uint texels, never filtered
  bool surfaceOnly = false; // a value only where a surface was drawn (normals, positions)
  // Defaults of the viewer's per-view settings.
  uint32_t channels = 0x7;  // components shown (bit c = component c)
  bool autoRange = false;
  bool falseColor = false;  // grey mappings: viridis (derived maps: the temporal views)
  float black = 0.0f, white = 1.0f;
  bool negativeSuspicious = true;  // negative values cannot be right here (highlighted)
  uint32_t predicate = gpu::kRangeAll;  // which texels count for the automatic range (and are drawn)
  std::optional<double> background;     // depth: the stored value where nothing was drawn
  std::string key;          // keyboard shortcut: "0" the first view, "2".."9" the next ones; "" none
  // A multisampled target's sample spread (sample_views.h), not a layout quantity's view: its
  // target's index (`quantity` is one the target holds).
  int spreadOf = -1;
};

// Every view of the layout, in layout order, the first colour view first (display, else radiance,
// else the first colour quantity): what the grid shows and the keys follow.
std::vector<ViewDef> layoutViews(const Layout& layout);

// A view by name: case, '_', '-' and spaces ignored ("hardware_depth" finds "HardwareDepth"); -1 none.
int findView(const std::vector<ViewDef>& views, const std::string& name);
// Every view's name, for messages ("Albedo, Normal, ...").
std::string viewNameList(const std::vector<ViewDef>& views);

// What a view's values count for gblens's coverage targets in a frame of lighting method `method`
// (FrameStats::method); other views: their unit.
std::string viewUnit(const ViewDef& def, const std::string& method);

// The label of component `c` of a view ("Normal.X"); "" beyond its components.
std::string componentLabel(const ViewDef& def, int c);

}  // namespace gb
