// CPU light classification and the ideal pair count.
#include "renderer/light_culling.h"

#include <algorithm>
#include <cmath>

#include "renderer/geometry.h"

namespace gb {

bool touchesNearPlane(const View& view, const glm::dvec3& c, double radius) {
  double circumradius = radius / kIcosahedronInradius;
  // Nearest point of the icosahedron's bounding sphere vs the near plane, with a margin for
  // the float rounding of the vertices on the GPU.
  return -c.z - circumradius <= view.znear * 1.001 + 1e-6 * circumradius;
}

// Sphere vs the view frustum in eye space (planes through the origin and the near/far planes).
static bool sphereInFrustum(const View& view, const glm::dvec3& c, double r) {
  if (-c.z + r < view.znear || -c.z - r > view.zfar) return false;
  const glm::dmat4& p = view.clipFromEye;
  // Side planes -w <= x_clip <= w (and y) with x_clip = P00 x + P20 z, w = -z: inside when
  // dot(n, c) <= 0 for each outward normal n below.
  const glm::dvec3 planes[4] = {
      {p[0][0], 0.0, p[2][0] + 1.0}, {-p[0][0], 0.0, 1.0 - p[2][0]},
      {0.0, p[1][1], p[2][1] + 1.0}, {0.0, -p[1][1], 1.0 - p[2][1]}};
  for (const glm::dvec3& n : planes)
    if (glm::dot(n, c) > r * glm::length(n)) return false;
  return true;
}

bool coversNoPixelCentre(const View& view, const glm::dvec3& c, double r) {
  const double depth = -c.z;
  if (depth - r <= view.znear) return false;  // reaches the near plane: unbounded projection
  const glm::dmat4& p = view.clipFromEye;
  // Along one screen axis: the lines through the eye tangent to the sphere's outline have
  // slopes t = lateral / depth solving (lateral - t depth)^2 = r^2 (1 + t^2); ndc = scale t - offset.
  auto noCentre = [&](double lateral, double scale, double offset, uint32_t size) {
    double d2 = depth * depth - r * r;
    double root = r * std::sqrt(lateral * lateral + d2);
    double t0 = (lateral * depth - root) / d2, t1 = (lateral * depth + root) / d2;
    double a = (scale * t0 - offset + 1.0) * 0.5 * size, b = (scale * t1 - offset + 1.0) * 0.5 * size;
    double lo = std::min(a, b) - 1e-3, hi = std::max(a, b) + 1e-3;
    // Pixel centres are at k + 0.5 for k in [0, size).
    double k0 = std::max(std::ceil(lo - 0.5), 0.0), k1 = std::min(std::floor(hi - 0.5), double(size) - 1.0);
    return k0 > k1;
  };
  return noCentre(c.x, p[0][0], p[2][0], view.width) || noCentre(c.y, p[1][1], p[2][1], view.height);
}

CpuImage eyeDepthFromHardware(const View& view, const CpuImage& ds) {
  CpuImage out;
  out.name = "depth";
  out.channels = {"Z"};
  out.width = ds.width;
  out.height = ds.height;
  out.data.resize(size_t(ds.width) * ds.height * sizeof(float));
  const double far = view.reversedZ ? 0.0 : 1.0;
  float* z = reinterpret_cast<float*>(out.data.data());
  for (uint32_t y = 0; y < ds.height; ++y)
    for (uint32_t x = 0; x < ds.width; ++x) {
      double d = ds.value(x, y, 0);
      z[size_t(y) * ds.width + x] = d == far ? 0.0f : float(-eyeFromHardwareDepth(view, x, y, d).z);
    }
  return out;
}

void classifyLights(const Scene& scene, const View& view, double time, FrameLights& out) {
  out.eye.resize(scene.lights.size());
  out.visible.clear();
  out.culledFrustum = out.culledEmpty = out.culledSubpixel = 0;
  std::vector<uint32_t> nearClass;
  for (size_t i = 0; i < scene.lights.size(); ++i) {
    const PointLightDesc& l = scene.lights[i];
    glm::dvec3 c = glm::dvec3(view.eyeFromWorld * glm::dvec4(lightPosition(l, time), 1.0));
    glm::dvec3 color = glm::dvec3(l.color) * l.intensity;
    out.eye[i].eyePositionRadius = glm::vec4(glm::vec3(c), float(l.radius));
    out.eye[i].color = glm::vec4(glm::vec3(color), 0.0f);
    if (!(l.radius > 0.0) || !(l.intensity > 0.0) || glm::dot(color, color) <= 0.0 || !std::isfinite(l.radius)) {
      out.culledEmpty++;
      continue;
    }
    if (!sphereInFrustum(view, c, l.radius)) {
      out.culledFrustum++;
      continue;
    }
    if (coversNoPixelCentre(view, c, l.radius)) {
      out.culledSubpixel++;
      continue;
    }
    if (touchesNearPlane(view, c, l.radius))
      nearClass.push_back(uint32_t(i));
    else
      out.visible.push_back(uint32_t(i));
  }
  out.stencilCount = uint32_t(out.visible.size());
  out.visible.insert(out.visible.end(), nearClass.begin(), nearClass.end());
}

static bool inside(const glm::dvec3& p, const gpu::PointLight& l) {
  glm::dvec3 d = p - glm::dvec3(l.eyePositionRadius);
  double r = l.eyePositionRadius.w;
  return glm::dot(d, d) < r * r;
}

uint64_t idealPairsBruteForce(const View& view, const CpuImage& depth, const std::vector<gpu::PointLight>& lights) {
  uint64_t n = 0;
  for (uint32_t y = 0; y < depth.height; ++y)
    for (uint32_t x = 0; x < depth.width; ++x) {
      double d = depth.value(x, y, 0);
      if (!(d > 0.0)) continue;
      glm::dvec3 p = eyeFromEyeDepth(view, x, y, float(d));
      for (const gpu::PointLight& l : lights)
        if (l.eyePositionRadius.w > 0.0f && inside(p, l)) ++n;
    }
  return n;
}

uint64_t idealPairs(const View& view, const CpuImage& depth, const std::vector<gpu::PointLight>& lights) {
  // Eye positions once per pixel.
  std::vector<glm::dvec3> pos(size_t(depth.width) * depth.height);
  std::vector<uint8_t> valid(pos.size());
  for (uint32_t y = 0; y < depth.height; ++y)
    for (uint32_t x = 0; x < depth.width; ++x) {
      double d = depth.value(x, y, 0);
      valid[size_t(y) * depth.width + x] = d > 0.0;
      if (d > 0.0) pos[size_t(y) * depth.width + x] = eyeFromEyeDepth(view, x, y, float(d));
    }
  uint64_t n = 0;
  for (const gpu::PointLight& l : lights) {
    glm::dvec3 c(l.eyePositionRadius);
    double r = l.eyePositionRadius.w;
    if (!(r > 0.0)) continue;
    // Screen rectangle of the sphere: project its eye-space AABB corners in front of the camera;
    // if any part is behind the near plane take the whole screen.
    int x0 = 0, y0 = 0, x1 = int(depth.width) - 1, y1 = int(depth.height) - 1;
    if (-c.z - r > view.znear) {
      double lo[2] = {1e300, 1e300}, hi[2] = {-1e300, -1e300};
      for (int k = 0; k < 8; ++k) {
        glm::dvec3 q = c + glm::dvec3((k & 1) ? r : -r, (k & 2) ? r : -r, (k & 4) ? r : -r);
        glm::dvec4 clip = view.clipFromEye * glm::dvec4(q, 1.0);
        for (int a = 0; a < 2; ++a) {
          double ndc = clip[a] / clip.w;
          lo[a] = std::min(lo[a], ndc);
          hi[a] = std::max(hi[a], ndc);
        }
      }
      auto toPixel = [](double ndc, uint32_t size) { return (ndc + 1.0) * 0.5 * size - 0.5; };
      x0 = std::max(x0, int(std::floor(toPixel(lo[0], depth.width))));
      x1 = std::min(x1, int(std::ceil(toPixel(hi[0], depth.width))));
      y0 = std::max(y0, int(std::floor(toPixel(lo[1], depth.height))));
      y1 = std::min(y1, int(std::ceil(toPixel(hi[1], depth.height))));
    }
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        size_t i = size_t(y) * depth.width + x;
        if (valid[i] && inside(pos[i], l)) ++n;
      }
  }
  return n;
}

}  // namespace gb

