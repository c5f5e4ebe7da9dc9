// The mapping from a view's settings to its GPU parameters.
#include "views/ui/view_params.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace gb {

using namespace gpu;

// A component mask of the view -> the source's channel mask.
static uint32_t channelMask(uint32_t components, const ViewGpuSource& src) {
  if (src.decoded || src.channelOf.empty()) return components;
  uint32_t mask = 0;
  for (uint32_t c = 0; c < 4; ++c)
    if ((components & (1u << c)) && c < src.channelOf.size()) mask |= 1u << src.channelOf[c];
  return mask;
}

gpu::ViewParams viewParams(const ViewDef& def, const ViewSettings& s, const ViewGpuSource& src, const ResolvedRange& range,
                           const Placement& pl, bool grid, std::optional<glm::ivec2> markTexel, glm::uvec2 shadowMapSize) {
  ViewParams p{};
  p.transform = glm::vec4(float(pl.originX), float(pl.originY), float(pl.scale), 0.0f);
  ViewMapping m = viewMapping(def, s);
  // One component of a live encoded normal: its decoded component (a raw channel of an octahedral
  // target is no component of the normal).
  if (src.nativeNormal && def.visual == Visual::Normal && m.mapping == kViewMapGrey) m.mapping = kViewMapNormal;
  uint32_t flags = m.flags;
  if (s.specials) flags |= kViewFlagSpecials;
  if (s.negative && def.negativeSuspicious) flags |= kViewFlagNegative;
  if (src.decoded) flags |= kViewFlagDecoded;
  if (src.nativeNormal && m.mapping == kViewMapNormal) flags |= kViewFlagNativeNormal;
  // The grid appears once a texel is 8 framebuffer pixels wide.
  if (grid && pl.scale >= 8.0) flags |= kViewFlagGrid;
  if (markTexel && !def.sun && !def.integer && !src.decoded) flags |= kViewFlagMark;
  const float gain = def.visual == Visual::Color ? std::exp2(s.exposure) : 1.0f;
  p.range = glm::vec4(range.black, range.white, std::clamp(float((pl.scale - 8.0) / 16.0), 0.25f, 0.6f), gain);
  // Decoded images mark their empty texels; live targets say it by a predicate.
  uint32_t predicate = src.decoded ? kRangeAll : def.predicate;
  p.mode = glm::uvec4(m.mapping, channelMask(m.mask, src), flags, predicate);
  if (markTexel) p.mark = glm::ivec4(markTexel->x, markTexel->y, int(shadowMapSize.x), int(shadowMapSize.y));
  float background = float(src.background.value_or(0.0));
  uint32_t bits = 0;
  std::memcpy(&bits, &background, 4);
  p.extra = glm::uvec4(s.stencilBits, bits, 0u, 0u);
  return p;
}

}  // namespace gb
