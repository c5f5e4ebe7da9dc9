// sphereScreenRect (light_rect.h): the tangent lines through the eye, per screen axis; and the
// culling rule for one light (cullLight), shared by light culling and the probe's light ledger.
#include "renderer/core/light_rect.h"

#include <algorithm>
#include <cmath>

#include "shaders/shared.h"

namespace gb {

// The pixel centres k + 0.5 (k in [0, size)) that the projection of a sphere in front of the
// eye can cover along one screen axis, as [k0, k1] (empty when k0 > k1). The lines through the
// eye tangent to the sphere's outline have slopes t = lateral / depth solving
// (lateral - t depth)^2 = r^2 (1 + t^2); ndc = scale t - offset. `margin` widens it, in pixels.
static void centreRange(double depth, double r, double lateral, double scale, double offset, uint32_t size,
                        double margin, int64_t& k0, int64_t& k1) {
  double d2 = depth * depth - r * r;
  double root = r * std::sqrt(lateral * lateral + d2);
  double t0 = (lateral * depth - root) / d2, t1 = (lateral * depth + root) / d2;
  double a = (scale * t0 - offset + 1.0) * 0.5 * size, b = (scale * t1 - offset + 1.0) * 0.5 * size;
  double lo = std::min(a, b) - margin, hi = std::max(a, b) + margin;
  k0 = int64_t(std::max(std::ceil(lo - 0.5), 0.0));
  k1 = int64_t(std::min(std::floor(hi - 0.5), double(size) - 1.0));
}

PixelRect sphereScreenRect(const Camera& camera, const glm::dvec3& c, double r, double margin) {
  const double depth = -c.z;
  if (depth + r <= 0.0) return {};  // behind the eye
  if (!(depth - r > 0.0) || !(depth * depth - r * r > 0.0))
    return {0, 0, int64_t(camera.width) - 1, int64_t(camera.height) - 1};  // reaches the eye's plane
  const glm::dmat4& p = camera.clipFromEye;
  PixelRect rect;
  centreRange(depth, r, c.x, p[0][0], p[2][0], camera.width, margin, rect.x0, rect.x1);
  centreRange(depth, r, c.y, p[1][1], p[2][1], camera.height, margin, rect.y0, rect.y1);
  return rect;
}

bool touchesNearPlane(const Camera& camera, const glm::dvec3& c, double radius) {
  double circumradius = radius / kIcosahedronInradius;
  // Nearest point of the icosahedron's bounding sphere vs the near plane, with a margin for
  // the float rounding of the vertices on the GPU.
  return -c.z - circumradius <= camera.znear * 1.001 + 1e-6 * circumradius;
}

// Sphere vs the camera frustum in eye space (planes through the origin and the near/far planes).
bool sphereInFrustum(const Camera& camera, const glm::dvec3& c, double r) {
  if (-c.z + r < camera.znear || -c.z - r > camera.zfar) return false;
  const glm::dmat4& p = camera.clipFromEye;
  // Side planes -w <= x_clip <= w (and y) with x_clip = P00 x + P20 z, w = -z: inside when
  // dot(n, c) <= 0 for each outward normal n below.
  const glm::dvec3 planes[4] = {
      {p[0][0], 0.0, p[2][0] + 1.0}, {-p[0][0], 0.0, 1.0 - p[2][0]},
      {0.0, p[1][1], p[2][1] + 1.0}, {0.0, -p[1][1], 1.0 - p[2][1]}};
  for (const glm::dvec3& n : planes)
    if (glm::dot(n, c) > r * glm::length(n)) return false;
  return true;
}

bool coversNoPixelCentre(const Camera& camera, const glm::dvec3& c, double r) {
  if (-c.z - r <= camera.znear) return false;  // reaches the near plane: unbounded projection
  return sphereScreenRect(camera, c, r, 1e-3).empty();
}

const char* name(LightCull c) {
  switch (c) {
    case LightCull::Empty: return "empty";
    case LightCull::Frustum: return "frustum_culled";
    case LightCull::SubPixel: return "sub_pixel";
    case LightCull::NearPlane: return "near_plane";
    case LightCull::Stencil: return "stencil";
  }
  return "?";
}

LightCull cullLight(const Camera& camera, const glm::dvec3& c, double radius, double intensity, const glm::dvec3& color) {
  if (!(radius > 0.0) || !(intensity > 0.0) || glm::dot(color, color) <= 0.0 || !std::isfinite(radius))
    return LightCull::Empty;
  if (!sphereInFrustum(camera, c, radius)) return LightCull::Frustum;
  if (coversNoPixelCentre(camera, c, radius)) return LightCull::SubPixel;
  return touchesNearPlane(camera, c, radius) ? LightCull::NearPlane : LightCull::Stencil;
}

// Olsson et al.'s slices: k = log(depth / near) / log(1 + 2 tan(fovy / 2) / tiles down), near-cubic
// clusters; where that needs more than kClusterMaxSlices between near and far, that many
// exponential slices span [near, far] instead.
ClusterSlicing clusterSlicing(const Camera& camera) {
  const uint32_t tilesY = (camera.height + gpu::kClusterTile - 1) / gpu::kClusterTile;
  const double perSlice = std::log2(1.0 + 2.0 * std::tan(camera.yfov * 0.5) / tilesY);
  double scale = 1.0 / perSlice;
  const double range = std::log2(camera.zfar / camera.znear);
  if (range * scale > double(gpu::kClusterMaxSlices)) scale = double(gpu::kClusterMaxSlices) / range;
  return {scale, -std::log2(camera.znear) * scale};
}

uint32_t clusterSlice(const ClusterSlicing& s, double eyeDepth) {
  const float k = std::floor(std::log2(std::max(float(eyeDepth), 1e-30f)) * float(s.scale) + float(s.bias));
  return uint32_t(std::clamp(k, 0.0f, float(gpu::kClusterMaxSlices - 1u)));
}

}  // namespace gb
