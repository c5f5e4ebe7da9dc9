// The view table (see view_table.h).
#include "views/analysis/view_table.h"

#include "renderer/core/assert.h"

namespace gb {

using namespace gpu;

static const ViewDef kViews[kViewKindCount] = {
    {.kind = ViewKind::Final, .name = "final", .label = "Final", .key = "0", .source = {Target::Final},
     .mapping = kViewMapColor, .channels = 0x7, .available = 0xF, .predicate = kRangeAll, .colour = true,
     .negativeSuspicious = true, .autoRange = false, .black = 0, .white = 1, .unit = ""},
    {.kind = ViewKind::Albedo, .name = "albedo", .label = "Albedo", .key = "2", .source = {Target::AlbedoSpecular},
     .mapping = kViewMapColor, .channels = 0x7, .available = 0xF, .predicate = kRangeAll, .colour = true,
     .negativeSuspicious = true, .autoRange = false, .black = 0, .white = 1, .unit = ""},
    {.kind = ViewKind::Normal, .name = "normal", .label = "Normal", .key = "3", .source = {Target::NormalShadow},
     .mapping = kViewMapNormal, .channels = 0x7, .available = 0xF, .predicate = kRangeAll, .colour = false,
     .negativeSuspicious = false, .autoRange = false, .black = -1, .white = 1, .unit = ""},
    {.kind = ViewKind::Depth, .name = "depth", .label = "Depth", .key = "4", .source = {Target::Depth},
     .mapping = kViewMapDepth, .channels = 0x1, .available = 0x1, .predicate = kRangePositive, .colour = false,
     .negativeSuspicious = true, .autoRange = true, .black = 0, .white = 1, .unit = "eye depth"},
    {.kind = ViewKind::Specular, .name = "specular", .label = "Specular", .key = "5",
     .source = {Target::AlbedoSpecular}, .mapping = kViewMapGrey, .channels = 0x8, .available = 0xF,
     .predicate = kRangeAll, .colour = false, .negativeSuspicious = true, .autoRange = false, .black = 0, .white = 1,
     .unit = ""},
    {.kind = ViewKind::Shadow, .name = "shadow", .label = "Shadow", .key = "6", .source = {Target::NormalShadow},
     .mapping = kViewMapGrey, .channels = 0x8, .available = 0xF, .predicate = kRangeAll, .colour = false,
     .negativeSuspicious = true, .autoRange = false, .black = 0, .white = 1, .unit = ""},
    {.kind = ViewKind::ShadowMap, .name = "shadowmap", .label = "Shadow map", .key = "7", .source = {Target::ShadowMap},
     .mapping = kViewMapDepth, .channels = 0x1, .available = 0x1, .predicate = kRangeBelowOne, .colour = false,
     .negativeSuspicious = true, .autoRange = true, .black = 0, .white = 1, .unit = "light depth"},
    {.kind = ViewKind::CoverageMasked, .name = "coverage_masked", .label = "Masked coverage", .key = "8",
     .source = {Target::CoverageMasked}, .mapping = kViewMapHeat, .channels = 0x1, .available = 0x1,
     .predicate = kRangeAll, .colour = false, .negativeSuspicious = false, .autoRange = true, .black = 0, .white = 1,
     .unit = "shader runs"},
    {.kind = ViewKind::CoverageFull, .name = "coverage_full", .label = "Full coverage", .key = "9",
     .source = {Target::CoverageFull}, .mapping = kViewMapHeat, .channels = 0x1, .available = 0x1,
     .predicate = kRangeAll, .colour = false, .negativeSuspicious = false, .autoRange = true, .black = 0, .white = 1,
     .unit = "lights"},
    {.kind = ViewKind::Hdr, .name = "hdr", .label = "HDR", .key = "", .source = {Target::Hdr}, .mapping = kViewMapColor,
     .channels = 0x7, .available = 0xF, .predicate = kRangeAll, .colour = true, .negativeSuspicious = true,
     .autoRange = false, .black = 0, .white = 1, .unit = ""},
    {.kind = ViewKind::HardwareDepth, .name = "hardware_depth", .label = "Hardware depth", .key = "",
     .source = {Target::DepthStencil}, .mapping = kViewMapDepth, .channels = 0x1, .available = 0x1,
     .predicate = kRangeNotFar, .colour = false, .negativeSuspicious = true, .autoRange = true, .black = 0, .white = 1,
     .unit = "depth"},
    {.kind = ViewKind::Stencil, .name = "stencil", .label = "Stencil", .key = "",
     .source = {Target::DepthStencil, true}, .mapping = kViewMapGrey, .channels = 0x1, .available = 0x1,
     .predicate = kRangeAll, .colour = false, .negativeSuspicious = false, .autoRange = false, .black = 0,
     .white = 255, .unit = ""},
};

const ViewDef& viewDef(ViewKind kind) {
  const ViewDef& d = kViews[int(kind)];
  GB_ASSERT(d.kind == kind);
  return d;
}

const char* viewName(ViewKind v) { return viewDef(v).name; }

const char* viewUnit(const ViewDef& def, const std::string& method) {
  if (def.kind == ViewKind::CoverageMasked) {
    if (method == "deferred") return "point-light fragment shader runs";
    if (method == "tiled") return "lights in the pixel's 16x16 tile list";
    if (method == "clustered") return "lights in the pixel's cluster list";
    if (method == "forward") return "lights looped over per fragment";
  }
  if (def.kind == ViewKind::CoverageFull) return "light volumes over the pixel (no depth or stencil test)";
  return def.unit;
}

bool parseView(const std::string& name, ViewKind& out) {
  for (const ViewDef& d : kViews)
    if (name == d.name) {
      out = d.kind;
      return true;
    }
  return false;
}

std::vector<std::string> viewNames() {
  std::vector<std::string> n;
  for (const ViewDef& d : kViews) n.push_back(d.name);
  return n;
}

const std::vector<ViewKind>& gridViews() {
  static const std::vector<ViewKind> v = {ViewKind::Final,  ViewKind::Albedo,    ViewKind::Normal,
                                          ViewKind::Depth,  ViewKind::Specular,  ViewKind::Shadow,
                                          ViewKind::ShadowMap, ViewKind::CoverageMasked, ViewKind::CoverageFull};
  return v;
}

std::string channelLabel(const ViewDef& def, int c) {
  if (def.source.stencil) return c == 0 ? "Stencil" : "";
  const std::vector<std::string>& names = channelNames(def.source.target);
  return size_t(c) < names.size() ? names[c] : "";
}

}  // namespace gb
