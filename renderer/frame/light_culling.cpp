// CPU light classification, the screen-disjoint layers of the per-light mask, and the ideal pair count.
#include "renderer/frame/light_culling.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <thread>
#include <vector>

#include "renderer/core/light_rect.h"
#include "renderer/scene/mesh_builder.h"

namespace gb {

// Pixels the light's icosahedron can rasterize: the rectangle of its bounding sphere, widened
// by a pixel so that rounding of the vertices on the GPU cannot reach outside it.
static PixelRect icosahedronPixels(const Camera& camera, const glm::dvec3& c, double radius) {
  return sphereScreenRect(camera, c, radius / kIcosahedronInradius, 1.0);
}

// Orders the stencil class [0, count) of `order` into layers of lights whose icosahedra cover
// disjoint pixels (so one stencil bit can serve a whole layer, drawn instanced) and returns the
// layer boundaries. Over 16x16-pixel cells, largest rectangles first: first fit into 64 layers at
// a time (a bit per layer per cell), the lights left after 4 such passes stacked above them, each
// one layer above the highest layer holding any of its cells. First fit to the end took 0.4 s a
// frame at 65536 lights (thousands of layers); this stays linear in lights x cells.
static std::vector<uint32_t> screenDisjointLayers(const Camera& camera, const std::vector<gpu::PointLight>& eye,
                                                  std::vector<uint32_t>& order, uint32_t count) {
  constexpr int64_t kCell = 16;
  constexpr int kFirstFitPasses = 4;
  const int64_t gw = (int64_t(camera.width) + kCell - 1) / kCell, gh = (int64_t(camera.height) + kCell - 1) / kCell;
  struct Cells {
    int64_t x0, y0, x1, y1;
  };
  std::vector<Cells> cells(count);
  for (uint32_t i = 0; i < count; ++i) {
    const gpu::PointLight& l = eye[order[i]];
    PixelRect rect = icosahedronPixels(camera, glm::dvec3(l.eyePositionRadius), l.eyePositionRadius.w);
    cells[i] = {std::clamp<int64_t>(rect.x0, 0, camera.width - 1) / kCell, std::clamp<int64_t>(rect.y0, 0, camera.height - 1) / kCell,
                std::clamp<int64_t>(rect.x1, 0, camera.width - 1) / kCell, std::clamp<int64_t>(rect.y1, 0, camera.height - 1) / kCell};
  }
  auto forCells = [&](uint32_t i, auto&& f) {
    for (int64_t y = cells[i].y0; y <= cells[i].y1; ++y)
      for (int64_t x = cells[i].x0; x <= cells[i].x1; ++x) f(size_t(y * gw + x));
  };
  std::vector<uint32_t> pending(count);
  for (uint32_t i = 0; i < count; ++i) pending[i] = i;
  auto area = [&](uint32_t i) { return (cells[i].x1 - cells[i].x0 + 1) * (cells[i].y1 - cells[i].y0 + 1); };
  std::stable_sort(pending.begin(), pending.end(), [&](uint32_t a, uint32_t b) { return area(a) > area(b); });

  std::vector<uint32_t> layerOf(count);
  std::vector<uint64_t> used(size_t(gw * gh));
  uint32_t base = 0;
  for (int pass = 0; pass < kFirstFitPasses && !pending.empty(); ++pass, base += 64) {
    std::fill(used.begin(), used.end(), 0);
    std::vector<uint32_t> later;
    for (uint32_t i : pending) {
      uint64_t taken = 0;
      forCells(i, [&](size_t c) { taken |= used[c]; });
      if (taken == ~uint64_t(0)) {
        later.push_back(i);
        continue;
      }
      const int bit = std::countr_one(taken);
      forCells(i, [&](size_t c) { used[c] |= uint64_t(1) << bit; });
      layerOf[i] = base + uint32_t(bit);
    }
    pending.swap(later);
  }
  std::vector<uint32_t> height(used.size(), base);
  for (uint32_t i : pending) {
    uint32_t layer = 0;
    forCells(i, [&](size_t c) { layer = std::max(layer, height[c]); });
    forCells(i, [&](size_t c) { height[c] = layer + 1; });
    layerOf[i] = layer;
  }
  // Dense layer numbers (a first-fit pass may leave some of its 64 unused).
  uint32_t top = 0;
  for (uint32_t i = 0; i < count; ++i) top = std::max(top, layerOf[i] + 1);
  std::vector<uint32_t> dense(top, 0);
  for (uint32_t i = 0; i < count; ++i) dense[layerOf[i]] = 1;
  uint32_t layers = 0;
  for (uint32_t& d : dense) d = d ? layers++ : 0;
  for (uint32_t i = 0; i < count; ++i) layerOf[i] = dense[layerOf[i]];
  std::vector<uint32_t> starts(layers + 1, 0);
  for (uint32_t i = 0; i < count; ++i) starts[layerOf[i] + 1]++;
  for (uint32_t k = 0; k < layers; ++k) starts[k + 1] += starts[k];
  std::vector<uint32_t> sorted(count), next(starts.begin(), starts.end() - 1);
  for (uint32_t i = 0; i < count; ++i) sorted[next[layerOf[i]]++] = order[i];  // visible-list order within a layer
  std::copy(sorted.begin(), sorted.end(), order.begin());
  return starts;
}

CpuImage eyeDepthFromHardware(const Camera& camera, const CpuImage& ds) {
  CpuImage out;
  out.name = "depth";
  out.channels = {"Z"};
  out.width = ds.width;
  out.height = ds.height;
  out.data.resize(size_t(ds.width) * ds.height * sizeof(float));
  const double far = camera.reversedZ ? 0.0 : 1.0;
  float* z = reinterpret_cast<float*>(out.data.data());
  for (uint32_t y = 0; y < ds.height; ++y)
    for (uint32_t x = 0; x < ds.width; ++x) {
      double d = ds.value(x, y, 0);
      z[size_t(y) * ds.width + x] = d == far ? 0.0f : float(-eyeFromHardwareDepth(camera, x, y, d).z);
    }
  return out;
}

void classifyLights(const Scene& scene, const Camera& camera, double time, bool layers, FrameLights& out) {
  out.eye.resize(scene.lights.size());
  out.visible.clear();
  out.culledFrustum = out.culledEmpty = out.culledSubpixel = 0;
  std::vector<uint32_t> nearClass;
  for (size_t i = 0; i < scene.lights.size(); ++i) {
    const PointLightDesc& l = scene.lights[i];
    glm::dvec3 c = glm::dvec3(camera.eyeFromWorld * glm::dvec4(lightPosition(l, time), 1.0));
    glm::dvec3 color = glm::dvec3(l.color) * l.intensity;
    out.eye[i].eyePositionRadius = glm::vec4(glm::vec3(c), float(l.radius));
    out.eye[i].color = glm::vec4(glm::vec3(color), 0.0f);
    switch (cullLight(camera, c, l.radius, l.intensity, color)) {
      case LightCull::Empty: out.culledEmpty++; break;
      case LightCull::Frustum: out.culledFrustum++; break;
      case LightCull::SubPixel: out.culledSubpixel++; break;
      case LightCull::NearPlane: nearClass.push_back(uint32_t(i)); break;
      case LightCull::Stencil: out.visible.push_back(uint32_t(i)); break;
    }
  }
  out.stencilCount = uint32_t(out.visible.size());
  out.layerStarts.clear();
  if (layers) out.layerStarts = screenDisjointLayers(camera, out.eye, out.visible, out.stencilCount);
  out.visible.insert(out.visible.end(), nearClass.begin(), nearClass.end());
}

static bool inside(const glm::dvec3& p, const gpu::PointLight& l) {
  glm::dvec3 d = p - glm::dvec3(l.eyePositionRadius);
  double r = l.eyePositionRadius.w;
  return glm::dot(d, d) < r * r;
}

uint64_t idealPairsBruteForce(const Camera& camera, const CpuImage& depth, const std::vector<gpu::PointLight>& lights) {
  uint64_t n = 0;
  for (uint32_t y = 0; y < depth.height; ++y)
    for (uint32_t x = 0; x < depth.width; ++x) {
      double d = depth.value(x, y, 0);
      if (!(d > 0.0)) continue;
      glm::dvec3 p = eyeFromEyeDepth(camera, x, y, float(d));
      for (const gpu::PointLight& l : lights)
        if (l.eyePositionRadius.w > 0.0f && inside(p, l)) ++n;
    }
  return n;
}

uint64_t idealPairs(const Camera& camera, const CpuImage& depth, const std::vector<gpu::PointLight>& lights) {
  // Eye positions once per pixel.
  std::vector<glm::dvec3> pos(size_t(depth.width) * depth.height);
  std::vector<uint8_t> valid(pos.size());
  for (uint32_t y = 0; y < depth.height; ++y)
    for (uint32_t x = 0; x < depth.width; ++x) {
      double d = depth.value(x, y, 0);
      valid[size_t(y) * depth.width + x] = d > 0.0;
      if (d > 0.0) pos[size_t(y) * depth.width + x] = eyeFromEyeDepth(camera, x, y, float(d));
    }
  // Lights are independent: counted on every core (4K at 65536 lights is a minute on one).
  auto countLight = [&](const gpu::PointLight& l) -> uint64_t {
    uint64_t n = 0;
    glm::dvec3 c(l.eyePositionRadius);
    double r = l.eyePositionRadius.w;
    if (!(r > 0.0)) return 0;
    // Only the pixels whose centre ray can meet the sphere: every position lies on its pixel's
    // centre ray (a pixel of margin for rounding).
    PixelRect rect = sphereScreenRect(camera, c, r, 1.0);
    const int64_t x1 = std::min<int64_t>(rect.x1, int64_t(depth.width) - 1);
    const int64_t y1 = std::min<int64_t>(rect.y1, int64_t(depth.height) - 1);
    for (int64_t y = rect.y0; y <= y1; ++y)
      for (int64_t x = rect.x0; x <= x1; ++x) {
        size_t i = size_t(y) * depth.width + size_t(x);
        if (valid[i] && inside(pos[i], l)) ++n;
      }
    return n;
  };
  const size_t threads = std::clamp<size_t>(std::thread::hardware_concurrency(), 1, 64);
  std::vector<uint64_t> counts(threads, 0);
  std::vector<std::thread> pool;
  for (size_t t = 0; t < threads; ++t)
    pool.emplace_back([&, t] {
      for (size_t i = t; i < lights.size(); i += threads) counts[t] += countLight(lights[i]);
    });
  for (std::thread& th : pool) th.join();
  uint64_t n = 0;
  for (uint64_t c : counts) n += c;
  return n;
}

}  // namespace gb

