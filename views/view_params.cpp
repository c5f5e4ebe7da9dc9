// View definitions (one table) and the mapping from settings to GPU parameters.
#include "views/view_params.h"

#include <algorithm>
#include <bit>
#include <cmath>

#include "renderer/vk/check.h"

namespace gb {

using namespace gpu;

// kind, label, key, source, mapping, channels, available, predicate, colour, negativeSuspicious,
// autoRange, black, white, unit
static const ViewDef kViews[kViewKindCount] = {
    {ViewKind::Final, "Final", "0", {Target::Final}, kViewMapColor, 0x7, 0xF, kRangeAll, true, true, false, 0, 1, ""},
    {ViewKind::Albedo, "Albedo", "2", {Target::AlbedoSpecular}, kViewMapColor, 0x7, 0xF, kRangeAll, true, true, false, 0, 1, ""},
    {ViewKind::Normal, "Normal", "3", {Target::NormalShadow}, kViewMapNormal, 0x7, 0xF, kRangeAll, false, false, false, -1, 1, ""},
    {ViewKind::Depth, "Depth", "4", {Target::Depth}, kViewMapDepth, 0x1, 0x1, kRangePositive, false, true, true, 0, 1, "eye depth"},
    {ViewKind::Specular, "Specular", "5", {Target::AlbedoSpecular}, kViewMapGrey, 0x8, 0xF, kRangeAll, false, true, false, 0, 1, ""},
    {ViewKind::Shadow, "Shadow", "6", {Target::NormalShadow}, kViewMapGrey, 0x8, 0xF, kRangeAll, false, true, false, 0, 1, ""},
    {ViewKind::ShadowMap, "Shadow map", "7", {Target::ShadowMap}, kViewMapDepth, 0x1, 0x1, kRangeBelowOne, false, true, true, 0, 1, "light depth"},
    {ViewKind::CoverageMasked, "Masked coverage", "8", {Target::CoverageMasked}, kViewMapHeat, 0x1, 0x1, kRangeAll, false, false, true, 0, 1, "shader runs"},
    {ViewKind::CoverageFull, "Full coverage", "9", {Target::CoverageFull}, kViewMapHeat, 0x1, 0x1, kRangeAll, false, false, true, 0, 1, "lights"},
    {ViewKind::Hdr, "HDR", "", {Target::Hdr}, kViewMapColor, 0x7, 0xF, kRangeAll, true, true, false, 0, 1, ""},
    {ViewKind::HardwareDepth, "Hardware depth", "", {Target::DepthStencil}, kViewMapDepth, 0x1, 0x1, kRangeNotFar, false, true, true, 0, 1, "depth"},
    {ViewKind::Stencil, "Stencil", "", {Target::DepthStencil, true}, kViewMapGrey, 0x1, 0x1, kRangeAll, false, false, false, 0, 255, ""},
};

const ViewDef& viewDef(ViewKind kind) {
  const ViewDef& d = kViews[int(kind)];
  GB_ASSERT(d.kind == kind);
  return d;
}

const std::vector<ViewKind>& gridViews() {
  static const std::vector<ViewKind> v = {ViewKind::Final,  ViewKind::Albedo,    ViewKind::Normal,
                                          ViewKind::Depth,  ViewKind::Specular,  ViewKind::Shadow,
                                          ViewKind::ShadowMap, ViewKind::CoverageMasked, ViewKind::CoverageFull};
  return v;
}

std::string channelLabel(const ViewDef& def, int c) {
  if (def.kind == ViewKind::Stencil) return c == 0 ? "Stencil" : "";
  std::vector<std::string> names = channelNames(def.source.target);
  return size_t(c) < names.size() ? names[c] : "";
}

ViewSettings defaultSettings(ViewKind kind) {
  const ViewDef& d = viewDef(kind);
  ViewSettings s;
  s.channels = d.channels;
  s.autoRange = d.autoRange;
  s.black = d.black;
  s.white = d.white;
  return s;
}

static uint32_t selected(const ViewDef& def, const ViewSettings& s) {
  uint32_t m = s.channels & def.available;
  return m ? m : def.channels;
}

std::vector<RangeRequest> rangeRequests(const ViewDef& def, const ViewSettings& s) {
  std::vector<RangeRequest> out;
  if (!s.autoRange) return out;
  uint32_t mask = selected(def, s);
  for (uint32_t c = 0; c < 4; ++c)
    if (mask & (1u << c)) out.push_back({def.source, def.source.stencil ? 0u : c, def.predicate});
  return out;
}

ResolvedRange resolveRange(const ViewDef& def, const ViewSettings& s, const std::vector<RangeStats>* stats) {
  ResolvedRange r;
  r.black = s.black;
  r.white = s.white;
  if (!s.autoRange || !stats || stats->empty()) return r;
  RangeStats all;
  double lo = 1e300, hi = -1e300;
  for (const RangeStats& st : *stats) {
    all.count += st.count;
    all.nan += st.nan;
    all.inf += st.inf;
    all.negative += st.negative;
    if (st.count) {
      lo = std::min(lo, st.lo);
      hi = std::max(hi, st.hi);
    }
  }
  if (all.count) {
    all.lo = lo;
    all.hi = hi;
  }
  r.stats = all;
  if (!all.count) return r;
  r.fromData = true;
  if (def.mapping == kViewMapHeat) {  // counts: 0 .. max, at least 1 (heatColor)
    r.black = 0.0f;
    r.white = float(std::max(hi, 1.0));
  } else {
    r.black = float(lo);
    r.white = float(hi > lo ? hi : lo + 1.0);  // a constant image: any non-empty span
  }
  return r;
}

gpu::ViewParams viewParams(const ViewDef& def, const ViewSettings& s, const ResolvedRange& range, const Placement& pl,
                           bool grid, std::optional<glm::ivec2> markTexel, glm::uvec2 shadowMapSize) {
  ViewParams p{};
  p.transform = glm::vec4(float(pl.originX), float(pl.originY), float(pl.scale), 0.0f);
  uint32_t mask = selected(def, s);
  uint32_t mapping = def.mapping;
  // One channel of a colour or normal target: shown as grey (as RenderDoc does).
  if ((mapping == kViewMapColor || mapping == kViewMapNormal) && std::popcount(mask) == 1) mapping = kViewMapGrey;
  // Alpha alongside colour channels is not displayable as colour: show the colour channels.
  if (mapping == kViewMapColor || mapping == kViewMapNormal) mask &= (std::popcount(mask & 0x7u) ? 0x7u : 0xFu);
  uint32_t flags = 0;
  const bool colourChannels = def.colour && (mask & 0x7u);
  if (colourChannels) flags |= kViewFlagSrgb;
  if (s.specials) flags |= kViewFlagSpecials;
  if (s.negative && def.negativeSuspicious) flags |= kViewFlagNegative;
  // The grid appears once a texel is 8 framebuffer pixels wide.
  if (grid && pl.scale >= 8.0) flags |= kViewFlagGrid;
  if (markTexel && def.source.target != Target::ShadowMap && !def.source.stencil &&
      def.mapping != kViewMapHeat)
    flags |= kViewFlagMark;
  p.range = glm::vec4(range.black, range.white, std::clamp(float((pl.scale - 8.0) / 16.0), 0.25f, 0.6f), 0.0f);
  p.mode = glm::uvec4(mapping, mask, flags, def.predicate);
  if (markTexel) p.mark = glm::ivec4(markTexel->x, markTexel->y, int(shadowMapSize.x), int(shadowMapSize.y));
  return p;
}

}  // namespace gb
