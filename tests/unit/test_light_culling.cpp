// The sub-pixel light rule on the CPU: a light skipped because its screen rectangle holds no pixel
// centre misses every pixel-centre ray (brute force); the sphere's screen rectangle against the
// pixels whose centre rays meet the sphere (brute force).
#include <gtest/gtest.h>

#include <cmath>

#include "renderer/core/camera.h"
#include "renderer/core/light_rect.h"
#include "renderer/frame/light_culling.h"
#include "renderer/scene/builtin.h"
#include "tests/support/scenes.h"

namespace gb {

// The camera both tests look through (far plane beyond every sphere).
static Camera testCamera(uint32_t width, uint32_t height) {
  Scene s = floorScene();
  setCamera(s, {0.0, 2.0, 6.0}, {0.3, 0.5, 0.0}, 0.8, 0.1, 500.0);
  return makeCamera(s.cameras[0], width, height, false);
}

// The fractional part of i * k: a deterministic spread over [0, 1).
static double cullSpread(int i, double k) { return i * k - std::floor(i * k); }

// Distance from `c` (eye space) to the ray from the eye through pixel (x, y)'s centre.
static double distanceToCentreRay(const Camera& v, const glm::dvec3& c, uint32_t x, uint32_t y) {
  glm::dvec3 dir = glm::normalize(eyeFromEyeDepth(v, x, y, 1.0));
  double along = glm::dot(c, dir);
  return along > 0.0 ? glm::length(c - along * dir) : glm::length(c);
}

// coversNoPixelCentre against brute force: for spheres of every size around the pixel scale,
// whenever it says "no centre", no pixel-centre ray comes within the radius of the centre.
TEST(LightCulling, ALightSkippedAsSubpixelMissesEveryPixelCentreRay) {
  const Camera v = testCamera(48, 32);
  int skipped = 0, kept = 0, subpixelKept = 0;
  for (int i = 0; i < 4000; ++i) {
    // Deterministic spread: depths 5..400, radii from 0.05 to 3 pixels' footprint.
    double u = cullSpread(i, 0.6180339887), w = cullSpread(i, 0.7548776662);
    double depth = 5.0 + 395.0 * cullSpread(i, 0.5698402910);
    double pixel = 2.0 * depth * std::tan(0.4) / v.height;
    double radius = pixel * (0.05 + 3.0 * cullSpread(i, 0.3141592653));
    glm::dvec3 c = eyeFromEyeDepth(v, u * v.width - 0.5, w * v.height - 0.5, depth);
    bool skip = coversNoPixelCentre(v, c, radius);
    bool hit = false;
    for (uint32_t y = 0; y < v.height && !hit; ++y)
      for (uint32_t x = 0; x < v.width && !hit; ++x) hit = distanceToCentreRay(v, c, x, y) < radius;
    if (skip) {
      ASSERT_FALSE(hit) << "light " << i << " skipped but reaches a pixel-centre ray";
      ++skipped;
    } else {
      ++kept;
      subpixelKept += radius < 0.5 * pixel && hit;
    }
  }
  EXPECT_GT(skipped, 200);
  EXPECT_GT(kept, 500);
  EXPECT_GT(subpixelKept, 20);  // smaller than a pixel but over a centre: kept, it lights that pixel
}

// sphereScreenRect against brute force: every pixel whose centre ray meets the sphere is inside
// the rectangle, and for spheres a few pixels wide within the frame each side of the rectangle is
// within a pixel of those pixels' bounding box. Spheres off screen, reaching the eye's plane and
// behind the eye included.
TEST(LightRect, HoldsEveryPixelWhoseCentreRayMeetsTheSphere) {
  const Camera v = testCamera(40, 24);
  int tight = 0, whole = 0, none = 0;
  for (int i = 0; i < 3000; ++i) {
    double u = cullSpread(i, 0.6180339887), w = cullSpread(i, 0.7548776662);
    double depth = -4.0 + 40.0 * cullSpread(i, 0.5698402910);
    // A third of the radii absolute (many reach the eye's plane), the rest 1% to 31% of the depth.
    double radius = i % 3 == 0 ? 0.02 + 6.0 * cullSpread(i, 0.3141592653) : std::abs(depth) * (0.01 + 0.3 * cullSpread(i, 0.3141592653));
    glm::dvec3 c = eyeFromEyeDepth(v, (1.6 * u - 0.3) * v.width, (1.6 * w - 0.3) * v.height, 1.0);
    c *= depth;  // the point at eye depth `depth` on that ray (behind the eye when negative)
    PixelRect rect = sphereScreenRect(v, c, radius, 1e-6);
    PixelRect box{int64_t(v.width), int64_t(v.height), -1, -1};  // bounding box of the hits
    for (uint32_t y = 0; y < v.height; ++y)
      for (uint32_t x = 0; x < v.width; ++x) {
        if (!(distanceToCentreRay(v, c, x, y) < radius)) continue;
        ASSERT_TRUE(x >= rect.x0 && x <= rect.x1 && y >= rect.y0 && y <= rect.y1)
            << "sphere " << i << ": pixel " << x << "," << y << " meets it outside the rectangle";
        box = {std::min<int64_t>(box.x0, x), std::min<int64_t>(box.y0, y), std::max<int64_t>(box.x1, x),
               std::max<int64_t>(box.y1, y)};
      }
    if (-c.z + radius <= 0.0) {
      EXPECT_TRUE(rect.empty()) << i;
      ++none;
    } else if (-c.z - radius <= 0.0) {
      EXPECT_EQ(rect.x1 - rect.x0 + 1, int64_t(v.width)) << i;
      EXPECT_EQ(rect.y1 - rect.y0 + 1, int64_t(v.height)) << i;
      ++whole;
    } else if (!box.empty() && radius / -c.z * v.height > 2.0 && rect.x0 > 0 && rect.y0 > 0 &&
               rect.x1 < int64_t(v.width) - 1 && rect.y1 < int64_t(v.height) - 1) {  // a few pixels wide, on screen
      EXPECT_LE(box.x0 - rect.x0, 1) << i;
      EXPECT_LE(rect.x1 - box.x1, 1) << i;
      EXPECT_LE(box.y0 - rect.y0, 1) << i;
      EXPECT_LE(rect.y1 - box.y1, 1) << i;
      ++tight;
    }
  }
  EXPECT_GT(tight, 150);
  EXPECT_GT(whole, 60);
  EXPECT_GT(none, 120);
}

}  // namespace gb
