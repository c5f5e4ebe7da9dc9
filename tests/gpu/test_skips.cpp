// Skip decisions of the frame function, read from the pass list (FrameStats::passes) without
// timing: no sun, no lights, no sky visible, static shadow map, lights that cover no pixel
// centre. Each skip is also checked to lose nothing (same pixels as the frame that ran it).
#include <cmath>

#include "renderer/core/camera.h"
#include "renderer/frame/light_culling.h"
#include "renderer/scene/builtin.h"
#include "tests/gpu/gpu_test.h"

namespace gb {

namespace {

const PassStat* pass(const FrameStats& st, const std::string& name) {
  for (const PassStat& p : st.passes)
    if (p.name == name) return &p;
  return nullptr;
}

// "ran" or the skip reason, so a failure message says what happened.
std::string state(const FrameStats& st, const std::string& name) {
  const PassStat* p = pass(st, name);
  if (!p) return "missing";
  return p->skipped ? "skipped: " + p->reason : "ran";
}

bool skippedFor(const FrameStats& st, const std::string& name, const std::string& reasonPart) {
  const PassStat* p = pass(st, name);
  return p && p->skipped && p->reason.find(reasonPart) != std::string::npos;
}

RenderOptions skipOptions() {
  RenderOptions o;
  o.width = 64;
  o.height = 40;
  o.lights = 0;
  return o;
}

}  // namespace

TEST_F(GpuTest, NoSunSkipsTheShadowMapAndNoLightsSkipEveryLightPass) {
  Scene scene = floorScene(20.0);  // no sun, no lights
  for (Method m : {Method::Deferred, Method::Tiled, Method::Forward}) {
    RenderOptions o = skipOptions();
    o.method = m;
    o.coverage = true;
    const FrameStats& st = render(scene, o);
    EXPECT_TRUE(skippedFor(st, "shadow_map", "no sun")) << state(st, "shadow_map");
    for (const char* p : {"light_mask", "point_lights"})
      EXPECT_TRUE(pass(st, p) && pass(st, p)->skipped) << name(m) << " " << p << ": " << state(st, p);
    for (const char* p : {"fairy_lights", "light_coverage"})
      EXPECT_TRUE(skippedFor(st, p, "no visible point lights")) << name(m) << " " << p << ": " << state(st, p);
    if (m == Method::Deferred) {
      EXPECT_TRUE(skippedFor(st, "point_lights", "no visible point lights"));
    }
  }
}

TEST_F(GpuTest, AStaticSunAndSceneReuseTheShadowMapUntilTheSunMoves) {
  Scene scene = builtinTemple(0);
  RenderOptions o = skipOptions();
  EXPECT_EQ(state(render(scene, o, {{Target::Hdr}}), "shadow_map"), "ran");
  CpuImage first = renderer(scene).readback[size_t(Target::Hdr)];
  const FrameStats& again = render(scene, o, {{Target::Hdr}});
  EXPECT_TRUE(skippedFor(again, "shadow_map", "reused")) << state(again, "shadow_map");
  EXPECT_EQ(renderer(scene).readback[size_t(Target::Hdr)].data, first.data);  // the reused map is the same map
  o.method = Method::Tiled;  // another method reads the same map
  EXPECT_TRUE(skippedFor(render(scene, o), "shadow_map", "reused"));
  scene.sun.toSun = glm::normalize(glm::dvec3(-0.4, 0.7, 0.2));
  EXPECT_EQ(state(render(scene, o), "shadow_map"), "ran");
  o.shadowMapSize = 512;  // new targets: nothing to reuse
  EXPECT_EQ(state(render(scene, o), "shadow_map"), "ran");
}

// The sky test: where no pixel showed sky in the last frame with this camera, size and
// geometry, the skybox is skipped; any change of those draws it (and counts) again.
TEST_F(GpuTest, TheSkyboxIsSkippedOnlyWhenTheSameViewShowedNoSky) {
  Scene scene = floorScene(50.0);
  setCamera(scene, {0.0, 3.0, 0.0}, {0.0, 0.0, -1.0});  // looking down at the floor: no sky
  RenderOptions o = skipOptions();
  std::vector<Scene> perMethod(3, scene);  // a renderer each: each starts without a count
  // Deferred and forward draw the sky as a raster pass; tiled and clustered write it from their
  // compute pass (ComputeMethodsWriteTheSkyTheSkyboxPassWouldDraw), so they never run it.
  for (Method m : {Method::Deferred, Method::Forward}) {
    const Scene& scene = perMethod[size_t(m)];
    o.method = m;
    const FrameStats& first = render(scene, o, {{Target::Hdr}});
    EXPECT_EQ(state(first, "skybox"), "ran") << name(m);  // first frame of this view: count
    EXPECT_EQ(first.skyPixels, 0);
    CpuImage drawn = renderer(scene).readback[size_t(Target::Hdr)];
    const FrameStats& second = render(scene, o, {{Target::Hdr}});
    EXPECT_TRUE(skippedFor(second, "skybox", "no sky visible")) << name(m) << ": " << state(second, "skybox");
    EXPECT_EQ(renderer(scene).readback[size_t(Target::Hdr)].data, drawn.data) << name(m);
  }
  // A new camera, or a new size, counts again; a view with sky never skips.
  setCamera(scene, {0.0, 3.0, 0.0}, {0.0, 2.5, -10.0});  // towards the horizon
  o.method = Method::Deferred;
  for (int frame = 0; frame < 2; ++frame) {
    const FrameStats& st = render(scene, o);
    EXPECT_EQ(state(st, "skybox"), "ran") << "frame " << frame;
    EXPECT_GT(st.skyPixels, 0);
  }
  setCamera(scene, {0.0, 3.0, 0.0}, {0.0, 0.0, -1.0});
  render(scene, o);
  EXPECT_TRUE(skippedFor(render(scene, o), "skybox", "no sky visible"));
  o.width = 48;
  EXPECT_EQ(state(render(scene, o), "skybox"), "ran");
  o.sky = false;
  EXPECT_TRUE(skippedFor(render(scene, o), "skybox", "sky disabled"));
}

TEST_F(GpuTest, LightsThatCoverNoPixelCentreAreSkippedAndChangeNoPixel) {
  Scene scene = floorScene(400.0);
  setCamera(scene, {0.0, 1.0, 0.0}, {0.0, 0.3, -100.0}, 0.8, 0.1, 1000.0);
  RenderOptions o = skipOptions();
  o.lights = 2;
  render(scene, o);
  const Camera& v = renderer(scene).camera;
  // Two tiny lights 200 units away (a pixel there is ~4 units across): one between pixel
  // centres, one on a pixel-centre ray.
  const double depth = 200.0, pixel = 2.0 * depth * std::tan(0.4) / o.height;
  auto onRay = [&](double px, double py) {
    glm::dvec3 eye = eyeFromEyeDepth(v, px, py, depth);
    return glm::dvec3(v.worldFromEye * glm::dvec4(eye, 1.0));
  };
  PointLightDesc between, over;
  between.center = onRay(20.5, 30.5);  // the corner between the centres of pixels 20..21, 30..31
  between.radius = 0.1 * pixel;
  over.center = onRay(21.0, 30.0);
  over.radius = 0.1 * pixel;
  for (PointLightDesc* l : {&between, &over}) {
    l->intensity = 50.0;
    l->color = glm::vec3(1.0f);
  }
  scene.lights = {between};
  const FrameStats& st = render(scene, o, {{Target::Hdr}});
  EXPECT_EQ(st.lightsCulledSubpixel, 1u);
  EXPECT_EQ(st.lightsVisible, 0u);
  EXPECT_TRUE(skippedFor(st, "point_lights", "no visible point lights")) << state(st, "point_lights");
  scene.lights = {over};
  const FrameStats& kept = render(scene, o, {{Target::Hdr}});
  EXPECT_EQ(kept.lightsCulledSubpixel, 0u);
  EXPECT_EQ(kept.lightsVisible, 1u);
  EXPECT_EQ(state(kept, "point_lights"), "ran");
}

}  // namespace gb
