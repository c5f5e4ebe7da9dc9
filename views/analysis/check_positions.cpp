// `gblens check`'s consistency test of the camera: positions rebuilt from each camera depth against
// the layout's stored position, at every surface pixel, each within the bound its storages and fp32
// arithmetic allow (see check.h PositionCheck). A wrong view matrix, offset or convention rebuilds
// most pixels metres off where the bound is micrometres: that is what it flags.
#include <algorithm>
#include <cmath>

#include "renderer/core/camera.h"
#include "renderer/core/decode.h"
#include "views/analysis/check.h"

namespace gb {

namespace {

// How far the rebuilt point moves when the stored depth moves by half its storage ulp.
double depthRounding(const FrameSnapshot& f, const Quantity& q, uint32_t x, uint32_t y, const glm::dvec3& eye) {
  const LayoutTarget& t = f.layout.targets[q.target];
  const double stored = storedValues(f, q, x, y)[0];
  const double half = 0.5 * storageUlp(t.format.type, t.format.encoding, stored);
  if (q.depth == DepthEncoding::Hardware) {
    const glm::dvec3 a = eyeFromHardwareDepth(f.camera, x, y, stored - half);
    const glm::dvec3 b = eyeFromHardwareDepth(f.camera, x, y, stored + half);
    return std::max(glm::length(a - eye), glm::length(b - eye));
  }
  // Eye and radial depths scale the point along its ray: the move is |P| times the relative error.
  const double value = std::abs(stored * q.scale + q.bias);
  return value > 0.0 ? glm::length(eye) * half * std::abs(q.scale) / value : 0.0;
}

// The rounding of a stored point: half an ulp of each coordinate in its format, combined.
double storedRounding(const LayoutTarget& t, const glm::dvec3& s) {
  double sum = 0.0;
  for (int c = 0; c < 3; ++c) {
    const double h = 0.5 * storageUlp(t.format.type, t.format.encoding, s[c]);
    sum += h * h;
  }
  return std::sqrt(sum);
}

PositionCheck compare(const FrameSnapshot& f, const Quantity& depth, const Quantity& stored, Severity severity) {
  PositionCheck p;
  p.depth = depth.name;
  p.stored = stored.name;
  const LayoutTarget& st = f.layout.targets[stored.target];
  p.storedFormat = st.format.name;
  p.severity = severity;
  std::vector<double> ratios;
  const double fp32 = 16.0 * std::ldexp(1.0, -24);  // the renderer computed both in fp32
  for (uint32_t y = 0; y < f.camera.height; ++y)
    for (uint32_t x = 0; x < f.camera.width; ++x) {
      if (!holds(f, depth, x, y) || !holds(f, stored, x, y) || !hasSurface(f, x, y)) continue;
      const std::optional<glm::dvec3> a = decodePosition(f, depth, x, y), b = decodePosition(f, stored, x, y);
      if (!a || !b || !std::isfinite(glm::length(*a)) || !std::isfinite(glm::length(*b))) continue;
      const glm::dvec3 s = spaceFromEye(f, stored.space, *b, true);
      const double bound = 2.0 * (storedRounding(st, s) + depthRounding(f, depth, x, y, *a) +
                                  fp32 * (glm::length(*a) + std::max({std::abs(s.x), std::abs(s.y), std::abs(s.z)})));
      const double distance = glm::length(*a - *b);
      const double ratio = bound > 0.0 ? distance / bound : (distance > 0.0 ? INFINITY : 0.0);
      ++p.pixels;
      ratios.push_back(ratio);
      if (ratio > 1.0) ++p.overBound;
      if (ratio > p.maxRatio || p.pixels == 1) p.maxRatio = ratio, p.x = x, p.y = y;
      p.maxDistance = std::max(p.maxDistance, distance);
    }
  if (!ratios.empty()) {
    std::nth_element(ratios.begin(), ratios.begin() + long(ratios.size() / 2), ratios.end());
    p.medianRatio = ratios[ratios.size() / 2];
  }
  // Most pixels ten times beyond their bound: not a few bad texels, the camera.
  p.cameraSuspect = p.pixels > 0 && p.medianRatio > 10.0;
  return p;
}

}  // namespace

std::vector<PositionCheck> checkPositions(const FrameSnapshot& f, const CheckPolicy& policy) {
  std::vector<PositionCheck> out;
  const Quantity* stored = f.layout.find(QuantityKind::Position);
  if (!stored || !layoutImage(f, stored->target)) return out;
  for (const Quantity& q : f.layout.quantities) {
    if (q.kind != QuantityKind::Depth || q.ofSun || !layoutImage(f, q.target)) continue;
    const Severity severity = policy.at(stored->name, "position");
    if (severity == Severity::Ignore) continue;
    out.push_back(compare(f, q, *stored, severity));
  }
  return out;
}

}  // namespace gb
