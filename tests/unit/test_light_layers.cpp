// The screen-disjoint layers of the per-light mask (CPU): lights sharing a stencil bit rasterize
// disjoint pixels.
#include <gtest/gtest.h>

#include <cmath>

#include "renderer/core/camera.h"
#include "renderer/frame/light_culling.h"
#include "renderer/scene/builtin.h"
#include "renderer/scene/mesh_builder.h"
#include "shaders/shading.h"
#include "tests/support/scenes.h"

namespace gb {

// The per-light mask draws a layer of lights instanced under one stencil bit, which is exact
// only if no two lights of a layer rasterize a common pixel. Checked against the pixel centres
// inside the bounding box of each light's 12 projected icosahedron vertices (double), which hold
// every pixel its triangles can cover, independently of the cell grid the layering works on.
TEST(LightLayers, LightsOfALayerRasterizeDisjointPixels) {
  Scene s = floorScene(40.0);
  setCamera(s, {0.0, 3.0, 12.0}, {0.0, 0.5, 0.0}, 0.9, 0.1, 200.0);
  for (int i = 0; i < 700; ++i) {  // deterministic spread over the floor, radii 0.1 to 4
    auto frac = [](double x) { return x - std::floor(x); };
    PointLightDesc l;
    l.center = {-30.0 + 60.0 * frac(i * 0.6180339887), 0.2 + 3.0 * frac(i * 0.5698402910),
                -60.0 + 70.0 * frac(i * 0.7548776662)};
    l.radius = 0.1 + 3.9 * frac(i * 0.3141592653) * frac(i * 0.2718281828);
    s.lights.push_back(l);
  }
  const Camera v = makeCamera(s.cameras[0], 320, 180, false);
  FrameLights fl;
  classifyLights(s, v, 0.0, true, fl);

  // Every light once: drawn, or counted as culled.
  std::vector<int> seen(s.lights.size(), 0);
  for (uint32_t i : fl.visible) seen[i]++;
  for (int n : seen) ASSERT_LE(n, 1);
  EXPECT_EQ(fl.visible.size() + fl.culledFrustum + fl.culledEmpty + fl.culledSubpixel, s.lights.size());
  ASSERT_GE(fl.layerStarts.size(), 2u);
  EXPECT_EQ(fl.layerStarts.front(), 0u);
  EXPECT_EQ(fl.layerStarts.back(), fl.stencilCount);

  struct Box {
    int64_t x0, y0, x1, y1;
  };
  auto centres = [&](uint32_t light) {
    const gpu::PointLight& l = fl.eye[light];
    const double scale = l.eyePositionRadius.w / kIcosahedronInradius;
    double lo[2] = {1e300, 1e300}, hi[2] = {-1e300, -1e300};
    for (const glm::vec3& p : icosahedron().vertices) {
      glm::dvec4 clip = v.clipFromEye * glm::dvec4(glm::dvec3(l.eyePositionRadius) + glm::dvec3(p) * scale, 1.0);
      EXPECT_GT(clip.w, v.znear);  // the stencil class lies in front of the near plane
      const double px[2] = {(clip.x / clip.w + 1.0) * 0.5 * v.width, (clip.y / clip.w + 1.0) * 0.5 * v.height};
      for (int a = 0; a < 2; ++a) lo[a] = std::min(lo[a], px[a]), hi[a] = std::max(hi[a], px[a]);
    }
    return Box{int64_t(std::ceil(lo[0] - 0.5)), int64_t(std::ceil(lo[1] - 0.5)), int64_t(std::floor(hi[0] - 0.5)),
               int64_t(std::floor(hi[1] - 0.5))};
  };
  size_t shared = 0;
  for (size_t k = 0; k + 1 < fl.layerStarts.size(); ++k) {
    std::vector<Box> boxes;
    for (uint32_t i = fl.layerStarts[k]; i < fl.layerStarts[k + 1]; ++i) boxes.push_back(centres(fl.visible[i]));
    shared += boxes.size() > 1;
    for (size_t a = 0; a < boxes.size(); ++a)
      for (size_t b = a + 1; b < boxes.size(); ++b) {
        const Box &p = boxes[a], &q = boxes[b];
        const bool overlap = std::max(p.x0, q.x0) <= std::min(p.x1, q.x1) && std::max(p.y0, q.y0) <= std::min(p.y1, q.y1) &&
                             std::max(p.x0, q.x0) < int64_t(v.width) && std::max(p.y0, q.y0) < int64_t(v.height) &&
                             std::min(p.x1, q.x1) >= 0 && std::min(p.y1, q.y1) >= 0;
        EXPECT_FALSE(overlap) << "layer " << k << ": lights " << fl.visible[fl.layerStarts[k] + a] << " and "
                              << fl.visible[fl.layerStarts[k] + b] << " can cover a common pixel";
      }
  }
  // Not vacuous: many layers hold several lights, and there are far fewer layers than lights.
  EXPECT_GT(fl.stencilCount, 300u);
  EXPECT_GT(shared, 10u);
  EXPECT_LT(fl.layerStarts.size() - 1, fl.stencilCount / 3);
}

}  // namespace gb
