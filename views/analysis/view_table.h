// The view table: every examination view under its one name (render --target, the viewer's keys
// and menus, docs), the target it reads and how it maps it for people. The CPU mapping
// (visualize.h), the viewer's GPU mapping (views/ui) and the command line all read this table.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "renderer/core/targets.h"
#include "shaders/shared.h"

namespace gb {

enum class ViewKind {
  Final, Albedo, Normal, Depth, Specular, Shadow, ShadowMap, CoverageMasked, CoverageFull,
  Hdr, HardwareDepth, Stencil
};
constexpr int kViewKindCount = 12;

// What a view shows of a target: its colour/depth aspect, or the stencil aspect of depth_stencil.
struct ViewSource {
  Target target = Target::Final;
  bool stencil = false;
};

struct ViewDef {
  ViewKind kind;
  const char* name;          // "albedo": render --target, --view, JSON
  const char* label;         // for people: "Albedo"
  const char* key;           // keyboard shortcut ("2") or "" (menu only)
  ViewSource source;
  uint32_t mapping;          // gpu::kViewMap*
  uint32_t channels;         // default channel mask (bit c = channel c of the target)
  uint32_t available;        // channels the target has
  uint32_t predicate;        // gpu::kRange*: texels that count for the automatic range
  bool colour;               // the RGB channels are linear colour (displayed sRGB-encoded)
  bool negativeSuspicious;   // negative values cannot be right here (highlighted)
  bool autoRange;            // default: the range comes from the data
  float black, white;        // default manual range
  const char* unit;          // of the mapped values, for the legend ("", "m", "lights")
};
const ViewDef& viewDef(ViewKind kind);
const char* viewName(ViewKind v);
// What a view's values count in a frame of lighting method `method` (FrameStats::method; empty:
// not known): views 8 and 9 count each method's own lighting work.
const char* viewUnit(const ViewDef& def, const std::string& method);
bool parseView(const std::string& name, ViewKind& out);
// Every view name, in table order ("final", "albedo", ...): the accepted values of --target / --view.
std::vector<std::string> viewNames();
// The nine views of the grid (key 1), in key order 0, 2..9.
const std::vector<ViewKind>& gridViews();
// Channel names of a view's target ("Albedo.R", ...), empty where the target has fewer.
std::string channelLabel(const ViewDef& def, int channel);

}  // namespace gb
