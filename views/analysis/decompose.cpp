// Lighting decomposition (decompose.h). Per surface pixel: the G-buffer as the lighting passes
// read it (probe.cpp lightingInputs), then every visible point light (shading.h's attenuation is
// exactly 0 at the radius, so summing all of them equals what any exact method shades). Terms are
// split by evaluating the shared formulas with one part zeroed: diffuse = albedo with specular 0
// (the ambient term, albedo x ambient, counts as diffuse), specular = black albedo with the
// stored specular; sun = the directional pass (ambient included); lighting = albedo 1.
#include "views/analysis/decompose.h"

#include <algorithm>
#include <atomic>
#include <thread>
#include <vector>

#include "renderer/core/progress.h"
#include "shaders/shading.h"
#include "views/analysis/probe_internal.h"

namespace gb {

const char* name(LightingTerm t) {
  static const char* names[] = {"lighting", "diffuse", "specular", "sun", "point_lights", "light_count"};
  return names[size_t(t)];
}

namespace {

void setRgb(CpuImage& img, uint32_t x, uint32_t y, const glm::dvec3& c) {
  float* p = reinterpret_cast<float*>(img.data.data()) + (size_t(y) * img.width + x) * 4;
  p[0] = float(c.r), p[1] = float(c.g), p[2] = float(c.b), p[3] = 1.0f;
}

void shadeRow(const FrameSnapshot& f, uint32_t y, Decomposition& out) {
  const glm::dvec3 sunDir = f.sunEyeDirection(), sunColor(f.sun.color), ambient(f.sky.ambient);
  const double sunOn = f.sun.enabled ? 1.0 : 0.0;
  for (uint32_t x = 0; x < f.camera.width; ++x) {
    LightingInputs in;
    if (!lightingInputs(f, x, y, in)) continue;
    const glm::dvec3 V = glm::normalize(-in.P), white(1.0), black(0.0);
    glm::dvec3 sun(0.0), sunDiffuse(0.0), sunSpecular(0.0), sunWhite(0.0), points(0.0), pointsDiffuse(0.0),
        pointsSpecular(0.0), pointsWhite(0.0);
    float count = 0.0f;
    if (in.unlit) {
      sun = sunDiffuse = shading::shadeUnlit(in.albedo);
      sunWhite = white;
    } else {
      const double shadow = sunOn * in.shadow;
      sun = shading::shadeDirectional(in.albedo, in.specular, in.normal, V, sunDir, sunColor, ambient, shadow);
      sunDiffuse = shading::shadeDirectional(in.albedo, 0.0, in.normal, V, sunDir, sunColor, ambient, shadow);
      sunSpecular = shading::shadeDirectional(black, in.specular, in.normal, V, sunDir, sunColor, ambient, shadow);
      sunWhite = shading::shadeDirectional(white, in.specular, in.normal, V, sunDir, sunColor, ambient, shadow);
      for (uint32_t i : f.visibleLights) {
        const gpu::PointLight& l = f.eyeLights[i];
        const glm::dvec3 c(l.eyePositionRadius), color(l.color);
        const double r = l.eyePositionRadius.w;
        if (!(glm::dot(c - in.P, c - in.P) < r * r)) continue;
        count += 1.0f;
        points += shading::shadePoint(in.albedo, in.specular, in.normal, in.P, c, r, color);
        pointsDiffuse += shading::shadePoint(in.albedo, 0.0, in.normal, in.P, c, r, color);
        pointsSpecular += shading::shadePoint(black, in.specular, in.normal, in.P, c, r, color);
        pointsWhite += shading::shadePoint(white, in.specular, in.normal, in.P, c, r, color);
      }
    }
    setRgb(out.images[size_t(LightingTerm::Lighting)], x, y, sunWhite + pointsWhite);
    setRgb(out.images[size_t(LightingTerm::Diffuse)], x, y, sunDiffuse + pointsDiffuse);
    setRgb(out.images[size_t(LightingTerm::Specular)], x, y, sunSpecular + pointsSpecular);
    setRgb(out.images[size_t(LightingTerm::Sun)], x, y, sun);
    setRgb(out.images[size_t(LightingTerm::PointLights)], x, y, points);
    CpuImage& n = out.images[size_t(LightingTerm::LightCount)];
    reinterpret_cast<float*>(n.data.data())[size_t(y) * n.width + x] = count;
  }
}

}  // namespace

bool decomposeLighting(const FrameSnapshot& f, Decomposition& out, std::string& error, unsigned threads) {
  error = lightingNotEvaluated(f);
  if (!error.empty()) return false;
  const uint32_t w = f.camera.width, h = f.camera.height;
  for (size_t t = 0; t < kLightingTermCount; ++t) {
    CpuImage& img = out.images[t];
    img = CpuImage{};
    img.name = name(LightingTerm(t));
    img.width = w, img.height = h;
    img.type = PixelType::F32;
    img.channels = t == size_t(LightingTerm::LightCount) ? std::vector<std::string>{"Count"}
                                                         : std::vector<std::string>{"R", "G", "B", "A"};
    img.data.assign(size_t(w) * h * img.texelBytes(), 0);
  }
  if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
  // The caller's progress (core/progress.h): a row counted as it finishes; cancelled, no row starts.
  WorkProgress* progress = currentProgress();
  std::atomic<uint32_t> next{0};
  std::vector<std::thread> pool;
  for (unsigned k = 0; k < threads; ++k)
    pool.emplace_back([&] {
      for (uint32_t y; (!progress || !progress->cancelled()) && (y = next.fetch_add(1)) < h;) {
        shadeRow(f, y, out);
        if (progress) progress->done.fetch_add(progress->weight, std::memory_order_relaxed);
      }
    });
  for (std::thread& t : pool) t.join();
  if (progress && progress->cancelled()) {
    error = "cancelled";
    return false;
  }
  return true;
}

}  // namespace gb
