// View settings and the mapping from settings to GPU parameters.
#include "views/ui/view_params.h"

#include <algorithm>
#include <bit>
#include <cmath>


namespace gb {

using namespace gpu;

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
