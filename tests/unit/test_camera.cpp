// Camera math against hand-computed values: projection, reconstruction from both depths.
#include <gtest/gtest.h>

#include "renderer/core/camera.h"

namespace gb {

TEST(Camera, ReconstructionFromEyeDepthAndHardwareDepthAgree) {
  CameraDesc c;
  c.worldFromEye = lookAt({0, 2, 5}, {0, 0, 0});
  c.yfov = 0.9;
  c.znear = 0.1;
  c.zfar = 100.0;
  for (bool reversed : {false, true}) {
    Camera v = makeCamera(c, 64, 48, reversed);
    for (double px : {0.0, 13.0, 63.0})
      for (double d : {0.2, 3.0, 77.0}) {
        glm::dvec3 e = eyeFromEyeDepth(v, px, 20.0, d);
        EXPECT_NEAR(-e.z, d, 1e-12);
        glm::dvec3 h = eyeFromHardwareDepth(v, px, 20.0, hardwareDepth(v, e));
        EXPECT_NEAR(glm::length(h - e), 0.0, 1e-9 * d);
      }
  }
}

TEST(Camera, PerspectiveMapsNearAndFarToTheDepthRange) {
  glm::dmat4 p = perspective(1.0, 1.5, 0.5, 50.0, false);
  auto depth = [&](double z) {
    glm::dvec4 c = p * glm::dvec4(0, 0, z, 1);
    return c.z / c.w;
  };
  EXPECT_NEAR(depth(-0.5), 0.0, 1e-15);
  EXPECT_NEAR(depth(-50.0), 1.0, 1e-15);
  glm::dmat4 r = perspective(1.0, 1.5, 0.5, 50.0, true);
  glm::dvec4 n = r * glm::dvec4(0, 0, -0.5, 1), f = r * glm::dvec4(0, 0, -50.0, 1);
  EXPECT_NEAR(n.z / n.w, 1.0, 1e-15);
  EXPECT_NEAR(f.z / f.w, 0.0, 1e-15);
  // Eye +Y is up on screen: clip y is negative (Vulkan y points down).
  glm::dvec4 up = p * glm::dvec4(0, 1, -2, 1);
  EXPECT_LT(up.y / up.w, 0.0);
}

}  // namespace gb
