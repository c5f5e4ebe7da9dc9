// Reference shading: ambient + sun + every point light at each pixel with shaders/shading.h in
// double. Lights are binned into 16x16-pixel tiles by their spheres' screen rectangles
// (renderer/core/light_rect.h) so thousands of lights stay cheap; a pixel's position lies on its
// centre ray, so a light outside its tile's list cannot reach it (the window falloff is exactly
// zero beyond the radius).
#include <algorithm>
#include <cmath>

#include "renderer/core/light_rect.h"
#include "renderer/reference/reference.h"
#include "shaders/shading.h"

namespace gb::reference {

std::vector<Light> eyeLights(const Scene& scene, const Camera& camera, double time) {
  std::vector<Light> out;
  for (const PointLightDesc& l : scene.lights) {
    Light e;
    e.eyePosition = glm::dvec3(camera.eyeFromWorld * glm::dvec4(lightPosition(l, time), 1.0));
    e.radius = l.radius;
    e.color = glm::dvec3(l.color) * l.intensity;
    if (!(e.radius > 0.0) || !std::isfinite(e.radius) || glm::dot(e.color, e.color) <= 0.0) continue;
    out.push_back(e);
  }
  return out;
}

Sun sunOf(const Scene& scene, const Camera& camera) {
  Sun s;
  s.enabled = scene.sun.enabled;
  s.toSunEye = glm::normalize(glm::dmat3(camera.eyeFromWorld) * scene.sun.toSun);
  s.color = glm::dvec3(scene.sun.color);
  s.ambient = glm::dvec3(scene.sky.ambient);
  return s;
}

ShadingInput shadingInput(const Surface& s) {
  ShadingInput in;
  in.geometry = s.hit;
  in.P = s.eye;
  in.N = s.normal;
  in.albedo = s.albedo;
  in.specular = s.specular;
  in.shadow = s.sunVisible == 0 ? 0.0 : 1.0;  // -1: the face turns away, the term does not matter
  in.unlit = s.unlit;
  return in;
}

glm::dvec3 shadeOne(const ShadingInput& s, const std::vector<Light>& lights, const Sun& sun) {
  if (!s.geometry) return glm::dvec3(0.0);
  if (s.unlit) return shading::shadeUnlit(s.albedo);
  const glm::dvec3 V = glm::normalize(-s.P);
  glm::dvec3 sum = shading::shadeDirectional(s.albedo, s.specular, s.N, V, sun.toSunEye, sun.color, sun.ambient,
                                             sun.enabled ? s.shadow : 0.0);
  for (const Light& l : lights) sum += shading::shadePoint(s.albedo, s.specular, s.N, s.P, l.eyePosition, l.radius, l.color);
  return sum;
}

Shaded shade(const std::vector<ShadingInput>& px, const Camera& camera, const std::vector<Light>& lights, const Sun& sun,
             unsigned threads) {
  const uint32_t w = camera.width, h = camera.height, tile = 16;
  const uint32_t tilesX = (w + tile - 1) / tile, tilesY = (h + tile - 1) / tile;
  std::vector<std::vector<uint32_t>> bins(size_t(tilesX) * tilesY);
  for (uint32_t i = 0; i < lights.size(); ++i) {
    // A pixel of margin for rounding (and positions read back from a G-buffer).
    const PixelRect r = sphereScreenRect(camera, lights[i].eyePosition, lights[i].radius, 1.0);
    if (r.empty()) continue;
    for (uint32_t ty = uint32_t(r.y0) / tile; ty <= uint32_t(r.y1) / tile; ++ty)
      for (uint32_t tx = uint32_t(r.x0) / tile; tx <= uint32_t(r.x1) / tile; ++tx) bins[size_t(ty) * tilesX + tx].push_back(i);
  }
  Shaded out;
  out.hdr.assign(px.size(), glm::dvec3(0.0));
  out.absSum.assign(px.size(), glm::dvec3(0.0));
  out.count.assign(px.size(), 0);
  parallelRows(h, threads, [&](uint32_t y) {
    for (uint32_t x = 0; x < w; ++x) {
      const size_t i = size_t(y) * w + x;
      const ShadingInput& s = px[i];
      if (!s.geometry) continue;
      if (s.unlit) {  // the lighting passes write the albedo and add no light
        out.hdr[i] = shading::shadeUnlit(s.albedo);
        out.absSum[i] = glm::abs(out.hdr[i]);
        out.count[i] = out.hdr[i] != glm::dvec3(0.0) ? 1 : 0;
        continue;
      }
      glm::dvec3 V = glm::normalize(-s.P);
      glm::dvec3 c = shading::shadeDirectional(s.albedo, s.specular, s.N, V, sun.toSunEye, sun.color, sun.ambient,
                                               sun.enabled ? s.shadow : 0.0);
      glm::dvec3 sum = c, absSum = glm::abs(c);
      uint32_t count = c != glm::dvec3(0.0) ? 1 : 0;
      for (uint32_t li : bins[size_t(y / tile) * tilesX + x / tile]) {
        const Light& l = lights[li];
        glm::dvec3 p = shading::shadePoint(s.albedo, s.specular, s.N, s.P, l.eyePosition, l.radius, l.color);
        if (p == glm::dvec3(0.0)) continue;
        sum += p;
        absSum += glm::abs(p);
        ++count;
      }
      out.hdr[i] = sum;
      out.absSum[i] = absSum;
      out.count[i] = count;
    }
  });
  return out;
}

}  // namespace gb::reference
