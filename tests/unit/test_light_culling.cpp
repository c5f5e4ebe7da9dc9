// The sub-pixel light rule on the CPU: a light skipped because its screen rectangle holds no pixel
// centre misses every pixel-centre ray (brute force).
#include <gtest/gtest.h>

#include <cmath>

#include "renderer/core/camera.h"
#include "renderer/light_culling.h"
#include "renderer/scene/builtin.h"
#include "tests/support/scenes.h"

namespace gb {

// coversNoPixelCentre against brute force: for spheres of every size around the pixel scale,
// whenever it says "no centre", no pixel-centre ray comes within the radius of the centre.
TEST(LightCulling, ALightSkippedAsSubpixelMissesEveryPixelCentreRay) {
  Scene s = floorScene();
  setCamera(s, {0.0, 2.0, 6.0}, {0.3, 0.5, 0.0}, 0.8, 0.1, 500.0);
  Camera v = makeCamera(s.cameras[0], 48, 32, false);
  int skipped = 0, kept = 0, subpixelKept = 0;
  for (int i = 0; i < 4000; ++i) {
    // Deterministic spread: depths 5..400, radii from 0.05 to 3 pixels' footprint.
    double u = (i * 0.6180339887) - std::floor(i * 0.6180339887), w = (i * 0.7548776662) - std::floor(i * 0.7548776662);
    double depth = 5.0 + 395.0 * ((i * 0.5698402910) - std::floor(i * 0.5698402910));
    double pixel = 2.0 * depth * std::tan(0.4) / v.height;
    double radius = pixel * (0.05 + 3.0 * ((i * 0.3141592653) - std::floor(i * 0.3141592653)));
    glm::dvec3 c = eyeFromEyeDepth(v, u * v.width - 0.5, w * v.height - 0.5, depth);
    bool skip = coversNoPixelCentre(v, c, radius);
    bool hit = false;
    for (uint32_t y = 0; y < v.height && !hit; ++y)
      for (uint32_t x = 0; x < v.width && !hit; ++x) {
        glm::dvec3 dir = glm::normalize(eyeFromEyeDepth(v, x, y, 1.0));
        double along = glm::dot(c, dir);
        hit = glm::length(c - along * dir) < radius;
      }
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

}  // namespace gb
