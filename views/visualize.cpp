// CPU mapping of targets to viewable sRGB images.
#include "views/visualize.h"

#include <algorithm>
#include <cmath>

#include "renderer/codec.h"

namespace gb {

static const char* const kViewNames[kViewKindCount] = {
    "final",  "albedo",    "normal",        "depth",         "specular", "shadow",
    "shadowmap", "coverage_masked", "coverage_full", "hdr", "hardware_depth", "stencil"};

const char* viewName(ViewKind v) { return kViewNames[int(v)]; }

bool parseView(const std::string& name, ViewKind& out) {
  for (int i = 0; i < kViewKindCount; ++i)
    if (name == kViewNames[i]) {
      out = ViewKind(i);
      return true;
    }
  return false;
}

std::vector<std::string> viewTargets(ViewKind v) {
  switch (v) {
    case ViewKind::Final: return {"final"};
    case ViewKind::Albedo:
    case ViewKind::Specular: return {"albedo_specular"};
    case ViewKind::Normal:
    case ViewKind::Shadow: return {"normal_shadow"};
    case ViewKind::Depth: return {"depth"};
    case ViewKind::ShadowMap: return {"shadow_map"};
    case ViewKind::CoverageMasked: return {"coverage_masked"};
    case ViewKind::CoverageFull: return {"coverage_full"};
    case ViewKind::Hdr: return {"hdr"};
    case ViewKind::HardwareDepth:
    case ViewKind::Stencil: return {"depth_stencil"};
  }
  return {};
}

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

Rgba8Image visualize(ViewKind view, const FrameImages& f) {
  const CpuImage* src = nullptr;
  switch (view) {
    case ViewKind::Final: src = f.final; break;
    case ViewKind::Albedo:
    case ViewKind::Specular: src = f.albedoSpecular; break;
    case ViewKind::Normal:
    case ViewKind::Shadow: src = f.normalShadow; break;
    case ViewKind::Depth: src = f.depth; break;
    case ViewKind::ShadowMap: src = f.shadowMap; break;
    case ViewKind::CoverageMasked: src = f.coverageMasked; break;
    case ViewKind::CoverageFull: src = f.coverageFull; break;
    case ViewKind::Hdr: src = f.hdr; break;
    case ViewKind::HardwareDepth:
    case ViewKind::Stencil: src = f.depthStencil; break;
  }
  Rgba8Image out;
  if (!src) return out;
  out.width = src->width;
  out.height = src->height;
  out.pixels.assign(size_t(out.width) * out.height * 4, 255);
  // Automatic ranges over what was drawn (depth > 0 for eye depth; < 1 for the shadow map;
  // hardware depth not at the far plane).
  const double farDepth = f.reversedZ ? 0.0 : 1.0;
  auto drawn = [&](double v) {
    return view == ViewKind::Depth ? v > 0.0 : view == ViewKind::ShadowMap ? v < 1.0 : v != farDepth;
  };
  double lo = 1e300, hi = -1e300, maxCount = 0;
  for (uint32_t y = 0; y < src->height; ++y)
    for (uint32_t x = 0; x < src->width; ++x) {
      double v = src->value(x, y, 0);
      if ((view == ViewKind::Depth || view == ViewKind::ShadowMap || view == ViewKind::HardwareDepth) && drawn(v)) {
        lo = std::min(lo, v);
        hi = std::max(hi, v);
      }
      if (view == ViewKind::CoverageMasked || view == ViewKind::CoverageFull) maxCount = std::max(maxCount, v);
    }
  if (hi <= lo) hi = lo + 1.0;
  for (uint32_t y = 0; y < src->height; ++y)
    for (uint32_t x = 0; x < src->width; ++x) {
      uint8_t* p = &out.pixels[(size_t(y) * out.width + x) * 4];
      switch (view) {
        case ViewKind::Final:
        case ViewKind::Albedo:
        case ViewKind::Hdr:
          for (int c = 0; c < 3; ++c) p[c] = encodeSrgb(src->value(x, y, c));
          break;
        case ViewKind::Specular: p[0] = p[1] = p[2] = encodeLinear(src->value(x, y, 3)); break;
        case ViewKind::Normal: {
          // Nothing drawn: the G-buffer clears to 0 in every channel (an octahedral (0, 0) is +Z).
          bool empty = true;
          for (uint32_t c = 0; c < src->channelCount(); ++c) empty = empty && src->value(x, y, c) == 0.0;
          DecodedNormal n = decodeNormalTexel(*src, x, y, f.normalFormat);
          for (int c = 0; c < 3; ++c) p[c] = empty ? 0 : encodeLinear(n.unit[c] * 0.5 + 0.5);
          break;
        }
        case ViewKind::Shadow: p[0] = p[1] = p[2] = encodeLinear(src->value(x, y, 3)); break;
        case ViewKind::Depth:
        case ViewKind::ShadowMap:
        case ViewKind::HardwareDepth: {
          double v = src->value(x, y, 0);
          p[0] = p[1] = p[2] = drawn(v) ? encodeLinear(1.0 - 0.9 * (v - lo) / (hi - lo)) : 0;  // near bright
          break;
        }
        case ViewKind::Stencil: p[0] = p[1] = p[2] = encodeLinear(src->value(x, y, 1) / 255.0); break;
        case ViewKind::CoverageMasked:
        case ViewKind::CoverageFull: heatColor(src->value(x, y, 0), maxCount, p); break;
      }
    }
  return out;
}

}  // namespace gb
