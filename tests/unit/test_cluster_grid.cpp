// The cluster grid's light assignment (renderer/core/cluster_grid.h) against brute force: every
// light that reaches a surface point, as the shader reconstructs and tests it in float, is in the
// list of the cell the shader looks up for that point; lists keep visible-list order; slices are
// Olsson's exponential ones, computed here with natural logarithms.
#include <gtest/gtest.h>

#include <cmath>

#include <glm/gtc/packing.hpp>

#include "renderer/core/cluster_grid.h"
#include "renderer/scene/builtin.h"
#include "tests/support/scenes.h"

namespace gb {

namespace {

double spread(int i, double k) { return i * k - std::floor(i * k); }

Camera gridCamera(glm::dvec3 eye, uint32_t w, uint32_t h, double znear, double zfar) {
  Scene s = floorScene();
  setCamera(s, eye, eye + glm::dvec3(0.3, -0.4, -1.0), 0.9, znear, zfar);
  return makeCamera(s.cameras[0], w, h, false);
}

// The surface point of pixel (x, y) at eye depth `d` as gbuffer_read.glsl's eyePosition() forms it (float).
glm::vec3 shaderPoint(const Camera& c, uint32_t x, uint32_t y, float d) {
  const glm::dmat4& p = c.clipFromEye;
  const glm::vec4 eyeRay(float(1.0 / p[0][0]), float(1.0 / p[1][1]), float(p[2][0]), float(p[2][1]));
  const glm::vec2 ndc = glm::vec2(x + 0.5f, y + 0.5f) * glm::vec2(1.0f / c.width, 1.0f / c.height) * 2.0f - 1.0f;
  const glm::vec2 xy = d * (ndc + glm::vec2(eyeRay.z, eyeRay.w)) * glm::vec2(eyeRay.x, eyeRay.y);
  return {xy.x, xy.y, -d};
}

// shading.h's test in float: the light adds something exactly when the attenuation is above 0.
bool reaches(const gpu::PointLight& l, const glm::vec3& P) {
  const glm::vec3 d = glm::vec3(l.eyePositionRadius) - P;
  const float x = glm::dot(d, d) / (l.eyePositionRadius.w * l.eyePositionRadius.w);
  const float w = std::clamp(1.0f - x, 0.0f, 1.0f);
  return w * w > 0.0f;
}

// Lights of every kind: spread over the screen and depth (past the far plane too), tiny to large,
// and the awkward ones: containing the camera, straddling the near plane, behind the camera.
std::vector<gpu::PointLight> someLights(const Camera& c, int n) {
  std::vector<gpu::PointLight> lights;
  for (int i = 0; i < n; ++i) {
    const double depth = c.znear * std::pow(1.3 * c.zfar / c.znear, spread(i, 0.5698402910));
    const glm::dvec3 p = eyeFromEyeDepth(c, spread(i, 0.6180339887) * 1.4 * c.width - 0.2 * c.width,
                                         spread(i, 0.7548776662) * 1.4 * c.height - 0.2 * c.height, depth);
    const double radius = depth * (0.002 + 0.3 * spread(i, 0.3141592653));
    lights.push_back({glm::vec4(glm::vec3(p), float(radius)), glm::vec4(1.0f)});
  }
  lights.push_back({glm::vec4(0.1f, -0.2f, 0.05f, 2.0f), glm::vec4(1.0f)});              // contains the camera
  lights.push_back({glm::vec4(0.3f, 0.1f, -float(c.znear), 0.5f), glm::vec4(1.0f)});    // straddles the near plane
  lights.push_back({glm::vec4(0.0f, 0.0f, 1.0f, 3.0f), glm::vec4(1.0f)});               // behind, reaching ahead
  lights.push_back({glm::vec4(0.0f, 0.0f, -float(c.zfar), float(c.zfar * 0.1)), glm::vec4(1.0f)});  // across the far plane
  return lights;
}

// For every `step`-th pixel and depths from the near to the far plane, and on both sides of
// every slice boundary: each light that reaches the point `toPoint` gives is listed in the cell the
// shader reads for that point.
template <class ToPoint>
int expectListed(const Camera& c, const ClusterGrid& grid, const std::vector<gpu::PointLight>& lights,
                 const std::vector<uint32_t>& visible, uint32_t step, ToPoint toPoint) {
  const GridShape& g = grid.shape;
  std::vector<float> depths;
  for (int k = 0; k <= 12; ++k) depths.push_back(float(c.znear * std::pow(c.zfar / c.znear, k / 12.0)));
  for (uint32_t k = 1; k < g.slices; ++k) {
    const float boundary = float(std::exp2((double(k) - g.bias) / g.scale));
    depths.insert(depths.end(), {std::nextafter(boundary, 0.0f), boundary, std::nextafter(boundary, 1e30f)});
  }
  int reached = 0;
  for (uint32_t y = 0; y < c.height; y += step)
    for (uint32_t x = (y / step) % step; x < c.width; x += step)
      for (float d : depths) {
        const glm::vec3 P = toPoint(x, y, d);
        const glm::uvec2 cell = grid.cells[g.cell(x / g.tile, y / g.tile, gridSlice(g, -P.z))];
        for (uint32_t v = 0; v < visible.size(); ++v) {
          if (!reaches(lights[visible[v]], P)) continue;
          ++reached;
          bool listed = false;
          for (uint32_t i = cell.x; i < cell.x + cell.y && !listed; ++i) listed = grid.listed[i] == v;
          if (!listed) {
            ADD_FAILURE() << "light " << visible[v] << " reaches pixel (" << x << ", " << y << ") at depth " << d
                          << " but is not in its cell";
            return reached;
          }
        }
      }
  return reached;
}

}  // namespace

TEST(ClusterGrid, EveryLightThatReachesAPointIsInItsCell) {
  const Camera c = gridCamera({1.0, 2.0, 3.0}, 200, 120, 0.1, 60.0);
  const std::vector<gpu::PointLight> lights = someLights(c, 300);
  std::vector<uint32_t> visible;
  for (uint32_t i = 0; i < lights.size(); i += 1 + (i % 7 == 3)) visible.push_back(i);  // not every light
  ClusterGrid grid;
  assignLights(c, lights, visible, {}, grid);
  const int reached = expectListed(c, grid, lights, visible, 3, [&](uint32_t x, uint32_t y, float d) {
    return shaderPoint(c, x, y, d);
  });
  EXPECT_GT(reached, 20000);  // the check saw many lit points
  // Lists hold visible-list positions in increasing order (the order the shader adds them in).
  for (const glm::uvec2& cell : grid.cells)
    for (uint32_t i = cell.x + 1; i < cell.x + cell.y; ++i) ASSERT_LT(grid.listed[i - 1], grid.listed[i]);
  EXPECT_GT(grid.occupiedCells(), grid.cells.size() / 10);
}

// A stored fp16 world position far from the origin: the point the shader reads is off its pixel's
// ray by the rounding; the grid's slack covers it.
TEST(ClusterGrid, StoredHalfPositionsFarFromTheOriginFindTheirLights) {
  const glm::dvec3 eye(2900.0, 40.0, -700.0);  // fp16 steps of 2 m there
  const Camera c = gridCamera(eye, 480, 288, 0.1, 60.0);
  const std::vector<gpu::PointLight> lights = someLights(c, 200);
  std::vector<uint32_t> visible(lights.size());
  for (uint32_t i = 0; i < visible.size(); ++i) visible[i] = i;
  ClusterGrid grid;
  const PositionSlack slack{std::ldexp(1.0, -11), glm::length(eye)};
  assignLights(c, lights, visible, slack, grid);
  const int reached = expectListed(c, grid, lights, visible, 7, [&](uint32_t x, uint32_t y, float d) {
    const glm::dvec3 world = glm::dvec3(c.worldFromEye * glm::dvec4(eyeFromEyeDepth(c, x, y, d), 1.0));
    const glm::vec3 stored = glm::unpackHalf4x16(glm::packHalf4x16(glm::vec4(glm::vec3(world), 1.0f)));
    return glm::vec3(c.eyeFromWorld * glm::dvec4(glm::dvec3(stored), 1.0));
  });
  EXPECT_GT(reached, 5000);
}

// Lights that barely reach across a slice boundary, onto points a few ULP from it: where the float
// slice of the shader and the double boundary of the CPU disagree, the grid's rounding margins decide.
TEST(ClusterGrid, PointsAtSliceBoundariesFindLightsThatBarelyReachThem) {
  const Camera c = gridCamera({0.0, 1.0, 0.0}, 64, 64, 0.1, 60.0);
  // The grid's slices span the lights' depths: two anchors fix them (every other light stays inside).
  std::vector<gpu::PointLight> lights = {{glm::vec4(0.0f, 0.0f, -0.4f, 0.01f), glm::vec4(1.0f)},
                                         {glm::vec4(0.0f, 0.0f, -58.0f, 0.01f), glm::vec4(1.0f)}};
  ClusterGrid probe;
  assignLights(c, lights, {0u, 1u}, {}, probe);
  const GridShape g = probe.shape;
  for (uint32_t k = 1; k < g.slices; ++k) {
    const double b = std::exp2((double(k) - g.bias) / g.scale);
    const uint32_t px = (k * 7) % c.width, py = (k * 13) % c.height;
    const glm::dvec3 ray = glm::normalize(eyeFromEyeDepth(c, px, py, 1.0));
    // Spheres whose nearest point on the pixel's ray sits just past the boundary (farther side) or
    // whose farthest point sits just before it (nearer side): large ones, and tiny ones that reach
    // only a few ULP of depth beyond the boundary's side.
    const double cosine = -ray.z;  // eye depth per unit distance along the ray
    for (double r : {0.02 * b / cosine, 1.5e-6 * b / cosine})
      for (double distance : {b * (1.0 + 3e-7) / cosine + r, b * (1.0 - 3e-7) / cosine - r})
        lights.push_back({glm::vec4(glm::vec3(ray * distance), float(r)), glm::vec4(1.0f)});
  }
  std::vector<uint32_t> visible(lights.size());
  for (uint32_t i = 0; i < visible.size(); ++i) visible[i] = i;
  ClusterGrid grid;
  assignLights(c, lights, visible, {}, grid);
  ASSERT_EQ(grid.shape.scale, g.scale);
  int reached = 0;
  for (uint32_t k = 1; k < g.slices; ++k) {
    const float b = float(std::exp2((double(k) - g.bias) / g.scale));
    const uint32_t px = (k * 7) % c.width, py = (k * 13) % c.height;
    float d = b * (1.0f - 2e-6f);
    for (int step = 0; step < 64; ++step, d = std::nextafter(d, 1e30f)) {
      const glm::vec3 P = shaderPoint(c, px, py, d);
      const glm::uvec2 cell = grid.cells[g.cell(px / g.tile, py / g.tile, gridSlice(g, -P.z))];
      for (uint32_t v = 2; v < lights.size(); ++v) {
        if (!reaches(lights[v], P)) continue;
        ++reached;
        bool listed = false;
        for (uint32_t i = cell.x; i < cell.x + cell.y && !listed; ++i) listed = grid.listed[i] == v;
        ASSERT_TRUE(listed) << "light " << v << " reaches pixel (" << px << ", " << py << ") at depth " << d;
      }
    }
  }
  EXPECT_GT(reached, 100);
}

// Slices are exponential between the two depths: slice = floor(S ln(d / near) / ln(far / near)).
TEST(ClusterGrid, SlicesAreExponentialBetweenTheTwoDepths) {
  const Camera c = gridCamera({0, 0, 0}, 64, 64, 0.1, 100.0);
  const GridShape g = gridShape(c, 2.0, 32.0);
  ASSERT_EQ(g.slices, uint32_t(gpu::kGridSlices));
  for (double d : {0.05, 1.0, 2.1, 3.3, 7.9, 15.2, 31.0, 50.0, 99.0}) {
    const double k = std::floor(g.slices * std::log(d / 2.0) / std::log(16.0));
    const double expected = std::clamp(k, 0.0, double(g.slices - 1));
    EXPECT_EQ(gridSlice(g, d), uint32_t(expected)) << "depth " << d;
  }
  EXPECT_EQ(g.tilesX, (64u + gpu::kGridTile - 1) / gpu::kGridTile);
}

}  // namespace gb
