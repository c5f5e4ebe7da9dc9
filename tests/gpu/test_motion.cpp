// The motion target (--motion on) against the CPU: each surface pixel's point rebuilt from the frame's
// eye depth and its drawn (jittered) camera, projected by the previous frame's camera and by this
// frame's unjittered one. The previous camera is computed here from the orbit formula as documented
// (renderer/core/camera_motion.h, docs/capture-format.md), not by the renderer's function; the jitter
// from the Halton sequence likewise. And the target's absence, with its reason, when it is off.
#include <cmath>

#include "renderer/core/camera.h"
#include "renderer/gpu/render_targets.h"
#include "renderer/scene/builtin.h"
#include "tests/gpu/gpu_test.h"

namespace gb {

namespace motion_test {

// camera_motion orbit as documented: 10 degrees per second about the world +Y axis through the scene's
// bounding-box centre, the camera turning with its position, and a rise of 0.02 R sin(2 pi t / 4 s).
glm::dmat4 orbitAt(const glm::dmat4& w0, const glm::dvec3& c, double radius, double t) {
  const double a = t * 10.0 * 3.14159265358979323846 / 180.0;
  auto turn = [a](const glm::dvec3& v) {
    return glm::dvec3(std::cos(a) * v.x + std::sin(a) * v.z, v.y, -std::sin(a) * v.x + std::cos(a) * v.z);
  };
  glm::dmat4 w(1.0);
  for (int k = 0; k < 3; ++k) w[k] = glm::dvec4(turn(glm::dvec3(w0[k])), 0.0);
  const double rise = 0.02 * radius * std::sin(2.0 * 3.14159265358979323846 * t / 4.0);
  w[3] = glm::dvec4(c + turn(glm::dvec3(w0[3]) - c) + glm::dvec3(0.0, rise, 0.0), 1.0);
  return w;
}

double radicalInverse(uint32_t i, uint32_t base) {
  double r = 0.0, scale = 1.0 / base;
  for (; i > 0; i /= base, scale /= base) r += scale * (i % base);
  return r;
}

// jitter halton: index 1 + (round(time / time_step) mod 16), offset (H2 - 0.5, H3 - 0.5) pixels.
glm::dvec2 haltonOffset(double time, double step) {
  const long long n = std::llround(time / step);
  const uint32_t i = uint32_t(((n % 16) + 16) % 16) + 1;
  return {radicalInverse(i, 2) - 0.5, radicalInverse(i, 3) - 0.5};
}

glm::dvec2 pixelOf(const glm::dmat4& clipFromWorld, const glm::dvec3& world, uint32_t w, uint32_t h) {
  const glm::dvec4 c = clipFromWorld * glm::dvec4(world, 1.0);
  return {(c.x / c.w * 0.5 + 0.5) * w, (c.y / c.w * 0.5 + 0.5) * h};
}

// RG16F keeps 11 significant bits: neighbouring values at |v| are 2^(floor(log2 |v|) - 10) apart
// (2^-24 among the subnormals). A conversion rounding to nearest is off by half that, one rounding
// toward zero (Vulkan allows either) by up to all of it: the bound takes the whole step.
double halfStep(double v) {
  const double a = std::abs(v);
  if (a < std::ldexp(1.0, -14)) return std::ldexp(1.0, -24);
  return std::ldexp(1.0, int(std::floor(std::log2(a))) - 10);
}

}  // namespace motion_test

TEST_F(GpuTest, MotionTargetMatchesTheOrbitReprojectedOnTheCpu) {
  using namespace motion_test;
  Scene scene = builtinTemple(8);
  RenderOptions base;
  base.width = 160;
  base.height = 90;
  base.lights = 8;
  base.shadowMapSize = 256;
  base.cameraMotion = CameraMotion::Orbit;
  base.motion = true;
  base.time = 1.3;
  base.timeStep = 0.1;
  struct Variant {
    Method method;
    Path path;
    Jitter jitter;
    GBufferClear clear;
  };
  const Variant variants[] = {{Method::Deferred, Path::TwoPass, Jitter::Off, GBufferClear::Auto},
                              {Method::Deferred, Path::TwoPass, Jitter::Halton, GBufferClear::Auto},
                              {Method::Deferred, Path::SinglePass, Jitter::Halton, GBufferClear::Auto},
                              {Method::Clustered, Path::TwoPass, Jitter::Halton, GBufferClear::Compute}};
  const glm::dvec3 centre = scene.bounds.center();
  const double radius = scene.bounds.radius();
  const glm::dmat4& w0 = scene.cameras[0].worldFromEye;
  for (const Variant& v : variants) {
    RenderOptions o = base;
    o.method = v.method;
    o.path = v.path;
    o.jitter = v.jitter;
    o.gbufferClear = v.clear;
    const std::string label = std::string(name(v.method)) + " " + name(v.path) + " jitter " + name(v.jitter);
    FrameSnapshot f = snapshot(scene, o, {Target::Depth, Target::Motion});
    ASSERT_EQ(f.absence(Target::Motion), Absent::No) << label;
    const CpuImage& motion = f.target(Target::Motion).image;
    const CpuImage& depth = f.target(Target::Depth).image;
    ASSERT_EQ(motion.width, o.width);
    ASSERT_EQ(motion.channels.size(), 2u);
    EXPECT_EQ(motion.type, PixelType::F16);

    // The frame's camera (the capture's) is the unjittered orbit at `time`.
    const Camera& cam = f.camera;
    const glm::dmat4 expectedNow = orbitAt(w0, centre, radius, o.time);
    for (int c = 0; c < 4; ++c)
      for (int k = 0; k < 4; ++k) ASSERT_NEAR(cam.worldFromEye[c][k], expectedNow[c][k], 1e-12) << label;
    ASSERT_EQ(cam.clipFromEye, perspective(cam.yfov, cam.aspect, cam.znear, cam.zfar, cam.reversedZ)) << label;
    // What was drawn: that projection moved by the jitter (pixels, +x right, +y down).
    const glm::dvec2 jitter = v.jitter == Jitter::Halton ? haltonOffset(o.time, o.timeStep) : glm::dvec2(0.0);
    Camera drawn = cam;
    drawn.clipFromEye[2][0] -= 2.0 * jitter.x / o.width;
    drawn.clipFromEye[2][1] -= 2.0 * jitter.y / o.height;
    EXPECT_NEAR(f.frameData.clipFromEye[2][0], drawn.clipFromEye[2][0], 1e-6) << label;
    const glm::dmat4 previousClipFromWorld =
        perspective(cam.yfov, cam.aspect, cam.znear, cam.zfar, cam.reversedZ) *
        glm::inverse(orbitAt(w0, centre, radius, o.time - o.timeStep));

    size_t surface = 0, bad = 0;
    double largest = 0.0, worst = 0.0;
    for (uint32_t y = 0; y < o.height; ++y)
      for (uint32_t x = 0; x < o.width; ++x) {
        const glm::dvec2 stored(motion.value(x, y, 0), motion.value(x, y, 1));
        const double d = depth.value(x, y, 0);
        if (d <= 0.0) {  // no geometry: cleared to 0
          if (stored != glm::dvec2(0.0)) ++bad;
          continue;
        }
        ++surface;
        const glm::dvec3 world(cam.worldFromEye * glm::dvec4(eyeFromEyeDepth(drawn, x, y, d), 1.0));
        const glm::dvec2 expected = pixelOf(previousClipFromWorld, world, o.width, o.height) -
                                    pixelOf(cam.clipFromWorld, world, o.width, o.height);
        largest = std::max(largest, glm::length(expected));
        for (int c = 0; c < 2; ++c) {
          // The RG16F step, and 1e-3 pixel for fp32 arithmetic and attribute interpolation (about
          // 1e-5 pixel at this size: fp32 NDCs times 80 pixels per unit).
          const double err = std::abs(stored[c] - expected[c]), bound = halfStep(expected[c]) + 1e-3;
          worst = std::max(worst, err / bound);
          if (err > bound) {
            if (bad < 5)
              ADD_FAILURE() << label << ": pixel " << x << "," << y << " channel " << c << " stored " << stored[c]
                            << " expected " << expected[c];
            ++bad;
          }
        }
      }
    EXPECT_EQ(bad, 0u) << label;
    EXPECT_GT(surface, size_t(o.width) * o.height / 2) << label;
    EXPECT_GT(largest, 0.5) << label << ": the orbit should move pixels visibly in 0.1 s";
    RecordProperty(label + " worst error / bound", std::to_string(worst));
  }
}

TEST_F(GpuTest, MotionTargetIsAbsentWithItsReasonWhenOffOrForward) {
  Scene scene = builtinTemple(8);
  RenderOptions o;
  o.width = 160;
  o.height = 90;
  o.lights = 8;
  o.shadowMapSize = 256;
  o.cameraMotion = CameraMotion::Orbit;
  o.time = 0.5;
  FrameSnapshot off = snapshot(scene, o, {Target::Depth});
  EXPECT_EQ(off.absence(Target::Motion), Absent::MotionOff);
  EXPECT_STREQ(absentText(off.absence(Target::Motion)), "not computed: motion off");
  EXPECT_FALSE(off.target(Target::Motion).present());
  for (Target t : readableTargets(renderer(scene), o)) EXPECT_NE(t, Target::Motion);
  EXPECT_EQ(renderer(scene).targets[size_t(Target::Motion)].image.desc.width, 1u) << "not computed: a 1x1 stand-in";
  o.motion = true;
  o.method = Method::Forward;
  FrameSnapshot forward = snapshot(scene, o, {Target::Final});
  EXPECT_EQ(forward.absence(Target::Motion), Absent::ForwardNoGBuffer);
  EXPECT_EQ(targetAbsence(Target::Motion, o), Absent::ForwardNoGBuffer);
}

}  // namespace gb
