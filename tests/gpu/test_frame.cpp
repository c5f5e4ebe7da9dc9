// The frame without point lights (Foundation issue): reconstruction, sky/stencil, shadows,
// resizing, determinism — each checked against an independent computation.
#include <cmath>

#include "renderer/core/camera.h"
#include "renderer/scene/builtin.h"
#include "tests/gpu/gpu_test.h"

namespace gb {

static RenderOptions smallOptions(uint32_t w, uint32_t h) {
  RenderOptions o;
  o.width = w;
  o.height = h;
  o.lights = 0;
  o.fairies = false;
  return o;
}

// Analytic: the eye-space point where the ray through a pixel centre meets the plane y = 0.
static glm::dvec3 floorHit(const Camera& v, double px, double py) {
  glm::dvec3 dirEye = eyeFromEyeDepth(v, px, py, 1.0);  // a point at eye depth 1 on the ray
  glm::dvec3 o = glm::dvec3(v.worldFromEye[3]);
  glm::dvec3 d = glm::dmat3(v.worldFromEye) * dirEye;
  double t = -o.y / d.y;
  return glm::dvec3(v.eyeFromWorld * glm::dvec4(o + t * d, 1.0));
}

TEST_F(GpuTest, ReconstructedPositionsMatchAnalyticFloorBothWays) {
  Scene scene = floorScene(50.0);
  setCamera(scene, {0, 3, 6}, {0, 0, -4}, 0.9, 0.1, 200.0);
  RenderOptions o = smallOptions(96, 64);
  // Stated tolerances. The rasterizer snaps vertices to 1/2^subPixelPrecisionBits of a pixel,
  // which moves the plane by up to half a step: a depth error of that fraction of the per-pixel
  // change of the surface distance. On top of that, eye depth is a float32 varying (relative
  // 1e-6) and hardware D32F depth loses about z/near ulps of depth (z <= 60, near 0.1: 1e-4).
  const double snap = std::ldexp(0.5, -int(ctx().properties.limits.subPixelPrecisionBits));
  const double eyeTol = 1e-6, hwTol = 1e-4;
  for (bool eyeDepth : {true, false}) {
    o.eyeDepth = eyeDepth;
    render(scene, o, {{Target::Depth, Target::DepthStencil}});
    Renderer& r = renderer(scene);
    const CpuImage& eye = r.readback[size_t(Target::Depth)];
    const CpuImage& hw = r.readback[size_t(Target::DepthStencil)];
    int checked = 0;
    for (uint32_t y = 0; y < o.height; ++y)
      for (uint32_t x = 0; x < o.width; ++x) {
        if (eye.value(x, y, 0) <= 0.0 || y + 1 >= o.height || x + 1 >= o.width) continue;
        glm::dvec3 expected = floorHit(r.camera, x, y);
        double dist = glm::length(expected);
        double gradient = std::max(glm::length(floorHit(r.camera, x + 1, y) - expected),
                                   glm::length(floorHit(r.camera, x, y + 1) - expected));
        glm::dvec3 fromEye = eyeFromEyeDepth(r.camera, x, y, eye.value(x, y, 0));
        glm::dvec3 fromHw = eyeFromHardwareDepth(r.camera, x, y, hw.value(x, y, 0));
        ASSERT_LT(glm::length(fromEye - expected), eyeTol * dist + snap * gradient) << x << "," << y;
        ASSERT_LT(glm::length(fromHw - expected), hwTol * dist + snap * gradient) << x << "," << y;
        ++checked;
      }
    EXPECT_GT(checked, int(o.width * o.height / 3));
  }
}

TEST_F(GpuTest, SkyPixelsAreExactlyThoseWithoutGeometryAndDirectionalLeavesThem) {
  Scene scene = builtinTemple(0);
  RenderOptions o = smallOptions(128, 72);
  o.sky = false;  // so hdr at sky pixels shows what the lighting passes wrote: nothing
  render(scene, o, {{Target::DepthStencil, Target::Hdr, Target::Depth}});
  Renderer& r = renderer(scene);
  const CpuImage& ds = r.readback[size_t(Target::DepthStencil)];
  const CpuImage& hdr = r.readback[size_t(Target::Hdr)];
  const CpuImage& eye = r.readback[size_t(Target::Depth)];
  int sky = 0, geometry = 0;
  for (uint32_t y = 0; y < o.height; ++y)
    for (uint32_t x = 0; x < o.width; ++x) {
      bool noGeometryStencil = ds.value(x, y, 1) == 0.0;
      bool farDepth = ds.value(x, y, 0) == 1.0;
      ASSERT_EQ(noGeometryStencil, farDepth) << x << "," << y;
      ASSERT_EQ(noGeometryStencil, eye.value(x, y, 0) == 0.0) << x << "," << y;
      double sum = hdr.value(x, y, 0) + hdr.value(x, y, 1) + hdr.value(x, y, 2);
      if (noGeometryStencil) {
        ASSERT_EQ(sum, 0.0) << "directional light touched sky pixel " << x << "," << y;
        ++sky;
      } else {
        ASSERT_EQ(ds.value(x, y, 1), 128.0);  // no lights: geometry stencil stays at the reference
        ASSERT_GT(sum, 0.0) << "geometry pixel without ambient " << x << "," << y;
        ++geometry;
      }
    }
  EXPECT_GT(sky, 100);
  EXPECT_GT(geometry, 1000);
}

TEST_F(GpuTest, ShadowOfABoxDarkensTheFloorByTheAmbientRatio) {
  Scene scene = floorScene(20.0);
  addBox(scene, {-0.5f, 0.0f, -0.5f}, {0.5f, 3.0f, 0.5f});
  scene.sun.enabled = true;
  scene.sun.toSun = glm::normalize(glm::dvec3(1.0, 1.0, 0.0));  // 45 degrees: shadow along -x
  scene.sun.color = glm::vec3(2.0f);
  scene.sky.ambient = glm::vec3(0.25f);
  setCamera(scene, {0, 12, 8}, {-1.5, 0, 0});
  RenderOptions o = smallOptions(128, 96);
  render(scene, o, {{Target::Hdr, Target::NormalShadow, Target::AlbedoSpecular}});
  Renderer& r = renderer(scene);
  const CpuImage& hdr = r.readback[size_t(Target::Hdr)];
  const CpuImage& ns = r.readback[size_t(Target::NormalShadow)];
  const CpuImage& albedo = r.readback[size_t(Target::AlbedoSpecular)];
  auto pixelOf = [&](glm::dvec3 world) {
    glm::dvec4 c = r.camera.clipFromWorld * glm::dvec4(world, 1.0);
    return glm::ivec2(int((c.x / c.w + 1) * 0.5 * o.width), int((c.y / c.w + 1) * 0.5 * o.height));
  };
  // (-2, 0, 0) lies in the box's shadow (the top edge at x = -0.5, y = 3 projects to x = -3.5);
  // (-2, 0, 2.5) is beside it in full sun.
  glm::ivec2 shadowed = pixelOf({-2.0, 0.0, 0.0}), lit = pixelOf({-2.0, 0.0, 2.5});
  EXPECT_EQ(ns.value(shadowed.x, shadowed.y, 3), 0.0);
  EXPECT_EQ(ns.value(lit.x, lit.y, 3), 1.0);
  // Albedo a (0.5 stored as 8-bit sRGB), specular 0, normal +Y:
  // lit = a*(ambient + sun*cos45), shadowed = a*ambient.
  const double expected = 0.25 / (0.25 + 2.0 * std::sqrt(0.5));
  for (int c = 0; c < 3; ++c) {
    double ratio = hdr.value(shadowed.x, shadowed.y, c) / hdr.value(lit.x, lit.y, c);
    EXPECT_NEAR(ratio, expected, expected * 2e-3) << "channel " << c;  // fp16 storage: 2^-11 each
    double a = albedo.value(shadowed.x, shadowed.y, c);
    EXPECT_NEAR(a, 0.5, 0.5 * 0.01);  // 8-bit sRGB step near 0.5
    // The GPU's sRGB decode may differ from the exact one by half an 8-bit step; then fp16.
    EXPECT_NEAR(hdr.value(shadowed.x, shadowed.y, c), a * 0.25, 0.25 * 0.5 / 255.0 + 0.125 * std::ldexp(1.0, -11));
  }
}

TEST_F(GpuTest, ChangingTheOutputSizeRecreatesTargets) {
  Scene scene = builtinTemple(16);
  for (auto [w, h] : {std::pair{64u, 48u}, {100u, 30u}, {64u, 48u}, {33u, 17u}}) {
    RenderOptions o = smallOptions(w, h);
    o.lights = 16;
    render(scene, o, {{Target::Final, Target::NormalShadow, Target::DepthStencil}});
    for (Target t : {Target::Final, Target::NormalShadow, Target::DepthStencil}) {
      EXPECT_EQ(renderer(scene).readback[size_t(t)].width, w);
      EXPECT_EQ(renderer(scene).readback[size_t(t)].height, h);
    }
  }
}

TEST_F(GpuTest, TheSameFrameTwiceGivesTheSamePixels) {
  Scene a = builtinTemple(64), b = builtinTemple(64);
  RenderOptions o = smallOptions(96, 54);
  o.lights = 64;
  o.time = 3.25;
  render(a, o, {{Target::Final, Target::Hdr}});
  render(b, o, {{Target::Final, Target::Hdr}});
  for (Target t : {Target::Final, Target::Hdr})
    EXPECT_EQ(renderer(a).readback[size_t(t)].data, renderer(b).readback[size_t(t)].data) << targetName(t);
}

// The frame graph compiles a render-pass group only when its shape (declarations and the state
// its targets arrive in) changed: an unchanged frame records from the compiled groups and must give
// the same pixels as a frame that compiled them; a changed option compiles again. (The second
// frame still compiles: its targets arrive in the layouts the first frame left, not undefined,
// and the shadow map is reused.)
TEST_F(GpuTest, AnUnchangedFrameReusesItsCompiledGroupsAndGivesTheSamePixels) {
  Scene scene = builtinTemple(32), fresh = builtinTemple(32);
  RenderOptions o = smallOptions(96, 54);
  o.lights = 32;
  const std::vector<Target> read = {Target::Final, Target::Hdr, Target::NormalShadow};
  const FrameStats first = render(scene, o, {read});
  EXPECT_GT(first.groupsCompiled, 0u);
  render(scene, o, {read});
  const FrameStats third = render(scene, o, {read});
  EXPECT_EQ(third.groupsCompiled, 0u);
  EXPECT_GE(third.groupsReused, 3u);  // gbuffer, lighting, tonemap (the shadow map is reused, not drawn)
  render(fresh, o, {read});
  for (Target t : read)
    EXPECT_EQ(renderer(scene).readback[size_t(t)].data, renderer(fresh).readback[size_t(t)].data) << targetName(t);
  RenderOptions single = o;
  single.path = Path::SinglePass;
  EXPECT_GT(render(scene, single, {read}).groupsCompiled, 0u);
  EXPECT_GT(render(scene, o, {read}).groupsCompiled, 0u);
  render(scene, o, {read});
  EXPECT_EQ(render(scene, o, {read}).groupsCompiled, 0u);
  for (Target t : read)
    EXPECT_EQ(renderer(scene).readback[size_t(t)].data, renderer(fresh).readback[size_t(t)].data) << targetName(t);
}

}  // namespace gb
