// Multisampled targets: the sample shown and the spread views (sample_views.h).
#include "views/analysis/sample_views.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace gb {

size_t frameSamples(const FrameSnapshot& f) {
  size_t n = 1;
  for (const TargetImage& t : f.images) n = std::max(n, t.samples.size());
  return n;
}

void showSample(FrameSnapshot& f, size_t k) {
  if (f.sampleShown == k) return;  // a frame as read shows sample 0 (its image is samples[0])
  for (TargetImage& t : f.images)
    if (t.samples.size() > 1) t.image = t.samples[std::min(k, t.samples.size() - 1)];
  f.sampleShown = uint32_t(k);
}

std::vector<ViewDef> spreadViews(const FrameSnapshot& f) {
  std::vector<ViewDef> out;
  for (uint32_t t = 0; t < f.images.size() && t < f.layout.targets.size(); ++t) {
    if (f.images[t].samples.size() < 2) continue;
    const std::vector<const Quantity*> held = f.layout.quantitiesOf(t);
    if (held.empty()) continue;
    ViewDef v;
    v.name = f.layout.targets[t].name + " spread";
    v.quantity = int(held[0] - f.layout.quantities.data());  // one the target holds: the hover names its stored texel
    v.spreadOf = int(t);
    v.kind = QuantityKind::Scalar;
    v.visual = Visual::Scalar;
    v.target = t;
    v.components = 1;
    v.componentNames = {v.name};
    v.unit = "largest difference between samples (stored channel values)";
    v.channels = 0x1;
    v.autoRange = true;
    v.negativeSuspicious = false;
    out.push_back(v);
  }
  return out;
}

double channelSpread(const TargetImage& t, uint32_t x, uint32_t y, uint32_t c) {
  const uint32_t lx = x - t.x0, ly = y - t.y0;
  if (t.image.encoding == Encoding::Uint) {
    std::vector<uint32_t> distinct;  // ids: how many values, not their distance
    for (const CpuImage& s : t.samples)
      if (const uint32_t v = s.raw(lx, ly, c); std::find(distinct.begin(), distinct.end(), v) == distinct.end())
        distinct.push_back(v);
    return double(distinct.size()) - 1.0;
  }
  double lo = INFINITY, hi = -INFINITY;
  for (const CpuImage& s : t.samples)
    if (const double v = s.value(lx, ly, c); std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v);
  return hi >= lo ? hi - lo : NAN;
}

std::optional<std::array<double, 4>> sampleSpread(const FrameSnapshot& f, uint32_t target, uint32_t x, uint32_t y) {
  const TargetImage& t = f.images[target];
  if (t.samples.size() < 2 || !t.contains(x, y)) return std::nullopt;
  for (const CpuImage& s : t.samples)
    if (s.width != t.image.width || s.height != t.image.height) return std::nullopt;
  double spread = -1.0;
  for (uint32_t c = 0; c < t.samples[0].channelCount(); ++c)
    if (const double s = channelSpread(t, x, y, c); std::isfinite(s)) spread = std::max(spread, s);
  if (spread < 0.0) return std::nullopt;
  return std::array<double, 4>{spread, 0.0, 0.0, 0.0};
}

}  // namespace gb
