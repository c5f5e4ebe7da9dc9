// CPU mapping of targets to viewable sRGB images.
#include "views/analysis/visualize.h"

#include <algorithm>
#include <cmath>

#include "renderer/core/codec.h"

namespace gb {

static uint8_t encodeSrgb(double linear) {
  linear = std::clamp(linear, 0.0, 1.0);
  double s = linear <= 0.0031308 ? linear * 12.92 : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
  return uint8_t(std::lround(s * 255.0));
}
static uint8_t encodeLinear(double v) { return uint8_t(std::lround(std::clamp(v, 0.0, 1.0) * 255.0)); }

void heatColor(double count, double max, uint8_t out[3]) {
  if (count <= 0.0) {
    out[0] = out[1] = out[2] = 0;
    return;
  }
  double t = std::clamp(count / std::max(max, 1.0), 0.0, 1.0);
  // blue -> cyan -> green -> yellow -> red
  const double stops[5][3] = {{0, 0, 1}, {0, 1, 1}, {0, 1, 0}, {1, 1, 0}, {1, 0, 0}};
  double f = t * 4.0;
  int i = std::min(int(f), 3);
  double a = f - i;
  for (int c = 0; c < 3; ++c) out[c] = encodeLinear(stops[i][c] * (1 - a) + stops[i + 1][c] * a);
}

// Texels that count for the automatic range of a depth view (gpu::kRange*, as on the GPU).
static bool inRange(uint32_t predicate, double v, double farDepth) {
  switch (predicate) {
    case gpu::kRangePositive: return v > 0.0;
    case gpu::kRangeBelowOne: return v < 1.0;
    case gpu::kRangeNotFar: return v != farDepth;
    default: return true;
  }
}

// The lowest selected channel of a single-channel mapping (grey, depth, heat).
static uint32_t firstChannel(const ViewDef& d) {
  for (uint32_t c = 0; c < 4; ++c)
    if (d.channels & (1u << c)) return c;
  return 0;
}

Rgba8Image visualize(ViewKind view, const FrameSnapshot& f) {
  const ViewDef& d = viewDef(view);
  const TargetImage& ti = f.target(d.source.target);
  Rgba8Image out;
  if (!ti.present()) return out;
  const CpuImage& src = ti.image;
  out.width = src.width;
  out.height = src.height;
  out.pixels.assign(size_t(out.width) * out.height * 4, 255);
  // The stencil is the second channel of depth_stencil's CPU copy.
  const uint32_t channel = d.source.stencil ? 1 : firstChannel(d);
  const double farDepth = f.options.reversedZ ? 0.0 : 1.0;
  double lo = 1e300, hi = -1e300, maxCount = 0;
  for (uint32_t y = 0; y < src.height; ++y)
    for (uint32_t x = 0; x < src.width; ++x) {
      double v = src.value(x, y, channel);
      if (d.mapping == gpu::kViewMapDepth && inRange(d.predicate, v, farDepth)) {
        lo = std::min(lo, v);
        hi = std::max(hi, v);
      }
      if (d.mapping == gpu::kViewMapHeat) maxCount = std::max(maxCount, v);
    }
  if (hi <= lo) hi = lo + 1.0;
  for (uint32_t y = 0; y < src.height; ++y)
    for (uint32_t x = 0; x < src.width; ++x) {
      uint8_t* p = &out.pixels[(size_t(y) * out.width + x) * 4];
      switch (d.mapping) {
        case gpu::kViewMapColor:
          for (int c = 0; c < 3; ++c) p[c] = d.colour ? encodeSrgb(src.value(x, y, c)) : encodeLinear(src.value(x, y, c));
          break;
        case gpu::kViewMapNormal: {
          // Nothing drawn: the G-buffer clears to 0 in every channel (an octahedral (0, 0) is +Z).
          bool empty = true;
          for (uint32_t c = 0; c < src.channelCount(); ++c) empty = empty && src.value(x, y, c) == 0.0;
          DecodedNormal n = decodeNormalTexel(src, x, y, f.options.normalFormat);
          for (int c = 0; c < 3; ++c) p[c] = empty ? 0 : encodeLinear(n.unit[c] * 0.5 + 0.5);
          break;
        }
        case gpu::kViewMapGrey:
          p[0] = p[1] = p[2] = encodeLinear((src.value(x, y, channel) - d.black) / (d.white - d.black));
          break;
        case gpu::kViewMapDepth: {
          double v = src.value(x, y, channel);
          p[0] = p[1] = p[2] = inRange(d.predicate, v, farDepth) ? encodeLinear(1.0 - 0.9 * (v - lo) / (hi - lo)) : 0;
          break;
        }
        case gpu::kViewMapHeat: heatColor(src.value(x, y, channel), maxCount, p); break;
      }
    }
  return out;
}

}  // namespace gb
