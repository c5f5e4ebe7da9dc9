// The pixels marked by a shadow-map texel (shadow_marks.h): every pixel's lookup placed as the probe
// places it, so the count, the box and the probe's "shadow-map texels" agree.
#include "views/analysis/shadow_marks.h"

#include <algorithm>

#include "views/analysis/probe.h"

namespace gb {

ShadowMarks shadowMarks(const FrameSnapshot& f, glm::ivec2 texel) {
  ShadowMarks out;
  glm::ivec2 lo(INT32_MAX), hi(INT32_MIN);
  const uint32_t width = f.options.width, height = f.options.height;
  for (uint32_t y = 0; y < height; ++y)
    for (uint32_t x = 0; x < width; ++x) {
      int32_t x0 = 0, y0 = 0;
      if (!shadowMapFootprint(f, x, y, x0, y0)) continue;
      ++out.lookups;
      out.readMin = out.lookups == 1 ? glm::ivec2(x0, y0) : glm::min(out.readMin, glm::ivec2(x0, y0));
      out.readMax = out.lookups == 1 ? glm::ivec2(x0 + 1, y0 + 1) : glm::max(out.readMax, glm::ivec2(x0 + 1, y0 + 1));
      const glm::ivec2 k = texel - glm::ivec2(x0, y0);
      if (k.x < 0 || k.x > 1 || k.y < 0 || k.y > 1) continue;
      ++out.pixels;
      lo = glm::min(lo, glm::ivec2(x, y)), hi = glm::max(hi, glm::ivec2(x, y));
      if (out.some.size() < kShadowMarksKept) out.some.push_back({int(x), int(y)});
    }
  if (out.pixels > 0) {
    out.box = RegionRect{uint32_t(lo.x), uint32_t(lo.y), uint32_t(hi.x - lo.x + 1), uint32_t(hi.y - lo.y + 1)};
  } else if (!f.sun.enabled) {
    out.note = "the frame has no sun: no pixel reads the shadow map";
  } else if (out.lookups == 0) {
    out.note = "no pixel of the frame has a surface the sun could shadow (no depth or position to place a lookup)";
  } else {
    const bool inside = texel.x >= out.readMin.x && texel.x <= out.readMax.x && texel.y >= out.readMin.y && texel.y <= out.readMax.y;
    const std::string read = "x " + std::to_string(out.readMin.x) + ".." + std::to_string(out.readMax.x) + ", y " +
                             std::to_string(out.readMin.y) + ".." + std::to_string(out.readMax.y) + ", by " +
                             std::to_string(out.lookups) + " pixels";
    out.note = inside ? "no pixel's lookup reads it, though it lies among the texels read (" + read +
                            "): there the map has more texels than the camera has pixels"
                      : "no pixel's lookup reads it: it lies outside the texels the frame's surfaces read (" + read +
                            "); the sun sees that part of the scene, the camera does not";
  }
  return out;
}

}  // namespace gb
