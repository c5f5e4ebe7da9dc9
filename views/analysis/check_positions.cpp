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
    // The rasterizer interpolates z / w itself (fp32, its own order of operations) before the depth
    // is stored: a few ulps, not the half ulp of storage alone. Four: a healthy lavapipe frame's
    // d32f depth reached 2.2 ulps (tests/subjects/foreign_deferred); a wrong camera is metres off.
    const double ulps = 4.0 * storageUlp(t.format.type, t.format.encoding, stored);
    const glm::dvec3 a = eyeFromHardwareDepth(f.camera, x, y, stored - ulps);
    const glm::dvec3 b = eyeFromHardwareDepth(f.camera, x, y, stored + ulps);
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

// The rasterizer places a triangle with its vertices snapped to a sub-pixel grid (Vulkan: at least
// 4 bits, subPixelPrecisionBits; desktop GPUs and lavapipe have 8): the depth at a pixel centre and
// the attributes interpolated there belong to points up to that far apart along the surface. gblens
// does not know the recording device's limit, so the spec's minimum: 1/16 pixel in x and in y.
constexpr double kPlacementPixels = 1.0 / 16.0;

// How far the surface rebuilt from `depth` moves per pixel at (x, y), in x plus in y (the smaller of
// the steps to either neighbour on each axis: a silhouette's jump is the other surface's).
double surfaceStep(const FrameSnapshot& f, const Quantity& depth, uint32_t x, uint32_t y, const glm::dvec3& at) {
  auto step = [&](int dx, int dy) {
    double best = INFINITY;
    for (int sign : {-1, 1}) {
      const int xx = int(x) + sign * dx, yy = int(y) + sign * dy;
      if (xx < 0 || yy < 0 || xx >= int(f.camera.width) || yy >= int(f.camera.height)) continue;
      if (!holds(f, depth, uint32_t(xx), uint32_t(yy)) || !hasSurface(f, uint32_t(xx), uint32_t(yy))) continue;
      const std::optional<glm::dvec3> p = decodePosition(f, depth, uint32_t(xx), uint32_t(yy));
      if (p) best = std::min(best, glm::length(*p - at));
    }
    return std::isfinite(best) ? best : 0.0;
  };
  return step(1, 0) + step(0, 1);
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
      // The stored point is interpolated from vertices computed in fp32: its rounding is that of
      // the vertices' coordinates, which may lie far beyond the point (a floor's corners): up to the
      // far plane, at most 100 times the point's own distance.
      const double eye = glm::length(*a);
      const double vertices = std::max(eye, std::min(f.camera.zfar, 100.0 * eye));
      const double bound = 2.0 * (storedRounding(st, s) + depthRounding(f, depth, x, y, *a) +
                                  fp32 * (eye + std::max({std::abs(s.x), std::abs(s.y), std::abs(s.z)}) + vertices) +
                                  kPlacementPixels * surfaceStep(f, depth, x, y, *a));
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
