// Frames in flight (submitFrame / finishFrames, renderer/frame/frame_slots.cpp): a burst whose camera,
// lights and time change every frame ends on the image a synchronous renderer draws for its last
// frame alone, bit for bit; every frame's statistics are complete and its light and cluster counts
// are the synchronous frame's; the skybox is skipped only on the count of a retired frame.
#include <glm/gtc/matrix_transform.hpp>

#include "renderer/passes/passes.h"
#include "renderer/readback/target_readback.h"
#include "renderer/scene/builtin.h"
#include "tests/gpu/gpu_test.h"

namespace gb {

namespace {

// A renderer of the test's own (GpuTest::renderer keys its renderers by the scene's address,
// which scenes made in a loop reuse).
struct OwnRenderer {
  Renderer r;
  explicit OwnRenderer(const Scene& scene) { initRenderer(r, GpuTest::ctx(), scene); }
  ~OwnRenderer() { destroyRenderer(r); }
};

// The last frame's targets, read back after the frames in flight finished.
std::vector<CpuImage> readBackLastFrame(Renderer& r, const std::vector<Target>& targets) {
  runAfterFrame(r, [&](FrameGraph& g) { addReadbackPass(g, r, targets); }, {});
  std::vector<CpuImage> out;
  for (Target t : targets) out.push_back(unpackReadback(r, t));
  return out;
}

// Frame i of the burst: the camera moved, one light brighter and larger, one more light off (so
// every frame's counts differ: i + 1 empty lights), another time.
void changeFrame(Scene& scene, RenderOptions& o, const glm::dmat4& baseCamera, int i) {
  scene.cameras[0].worldFromEye = glm::translate(glm::dmat4(1.0), glm::dvec3(0.15 * i, -0.05 * i, 0.2 * i)) * baseCamera;
  PointLightDesc& l = scene.lights[size_t(7 * i) % scene.lights.size()];
  l.intensity *= 4.0;
  l.radius *= 1.5;
  scene.lights[size_t(7 * i + 3) % scene.lights.size()].intensity = 0.0;
  o.time = 0.5 + 0.3 * i;
}

}  // namespace

TEST_F(GpuTest, ABurstInFlightEndsOnTheSynchronousFrameWithCompleteStatistics) {
  struct Case {
    Method method;
    LightSetup setup;
  };
  const bool gpuSetup = ctx().features.float64;
  for (const Case& c : {Case{Method::Deferred, LightSetup::Auto}, Case{Method::Tiled, LightSetup::Cpu},
                        Case{Method::Clustered, gpuSetup ? LightSetup::Gpu : LightSetup::Cpu},
                        Case{Method::Forward, LightSetup::Auto}}) {
    const std::string what = name(c.method);
    Scene scene = builtinTemple(64);
    scene.generatedLights = false;
    const glm::dmat4 baseCamera = scene.cameras[0].worldFromEye;
    RenderOptions o;
    o.width = 96;
    o.height = 54;
    o.method = c.method;
    o.lightSetup = c.setup;
    o.fairies = true;
    OwnRenderer pipelined(scene);
    Renderer& r = pipelined.r;
    Scene syncScene = scene;  // a synchronous renderer follows the same frames
    OwnRenderer sync(syncScene);
    const int frames = 6;
    std::vector<FrameStats> expected;
    for (int i = 0; i < frames; ++i) {
      changeFrame(scene, o, baseCamera, i);
      submitFrame(r, o);
      syncScene.cameras = scene.cameras;
      syncScene.lights = scene.lights;
      expected.push_back(renderFrame(sync.r, o));
    }
    const std::vector<FrameStats> got = finishFrames(r);
    ASSERT_EQ(got.size(), size_t(frames)) << what;
    for (int i = 0; i < frames; ++i) {
      const FrameStats &g = got[size_t(i)], &e = expected[size_t(i)];
      EXPECT_EQ(g.method, name(c.method));
      EXPECT_EQ(g.lightSetup, e.lightSetup) << what;
      EXPECT_EQ(g.lights, e.lights) << what << " frame " << i;
      EXPECT_EQ(g.lightsVisible, e.lightsVisible) << what << " frame " << i;
      EXPECT_EQ(g.lightsInside, e.lightsInside) << what << " frame " << i;
      EXPECT_EQ(g.stencilLayers, e.stencilLayers) << what << " frame " << i;
      EXPECT_EQ(g.lightsCulledFrustum, e.lightsCulledFrustum) << what << " frame " << i;
      EXPECT_EQ(g.lightsCulledEmpty, e.lightsCulledEmpty) << what << " frame " << i;
      EXPECT_EQ(g.lightsCulledSubpixel, e.lightsCulledSubpixel) << what << " frame " << i;
      EXPECT_EQ(g.clusters.valid, e.clusters.valid) << what;
      EXPECT_EQ(g.clusters.clusters, e.clusters.clusters) << what << " frame " << i;
      EXPECT_EQ(g.clusters.listEntries, e.clusters.listEntries) << what << " frame " << i;
      EXPECT_GT(g.cpuMs, 0.0);
      EXPECT_GE(g.frameMs, g.cpuMs);
      ASSERT_EQ(g.passes.size(), e.passes.size()) << what;
      if (!ctx().features.timestamps) continue;
      EXPECT_GT(g.gpuMs, 0.0) << what << " frame " << i;
      double spans = 0.0;  // the passes and the gaps before them tile the frame's GPU time
      for (const PassStat& p : g.passes) {
        if (p.skipped) continue;
        EXPECT_GE(p.ms, 0.0) << what << " frame " << i << " " << p.name << ": no GPU time";
        EXPECT_GE(p.beforeMs, 0.0) << what << " frame " << i << " " << p.name << ": starts before the pass before it ends";
        spans += p.beforeMs + p.ms;
      }
      EXPECT_NEAR(spans, g.gpuMs, 1e-6 * g.gpuMs + 1e-9) << what << " frame " << i;
    }
    EXPECT_GT(got.back().lightsVisible, 0u) << what;
    EXPECT_EQ(got.back().lightsCulledEmpty, uint32_t(frames)) << what;
    // The last frame alone, on a fresh renderer.
    const std::vector<Target> targets = {Target::Hdr, Target::Final};
    const std::vector<CpuImage> last = readBackLastFrame(r, targets);
    const Scene alone = scene;
    OwnRenderer fresh(alone);
    renderFrame(fresh.r, o, {targets});
    for (size_t t = 0; t < targets.size(); ++t)
      EXPECT_EQ(differingTexels(last[t], fresh.r.readback[size_t(targets[t])]), 0u)
          << what << ": " << targetName(targets[t]) << " of the burst's last frame";
  }
}

// The skybox is skipped when the last counted frame with this camera drew no sky pixel; with
// frames in flight that count must come from a retired frame. The decisions are predicted from
// the camera sequence alone: at frame i's submission the frames up to i - kFrameSlots are
// retired (the slot it takes was theirs), the later ones are pending.
TEST_F(GpuTest, TheSkyboxSkipUsesOnlyRetiredFrames) {
  Scene scene = builtinTemple(16);
  scene.cameras.push_back(lookAtCamera("down", {0.0, 3.0, 0.0}, {0.0, 0.0, 0.001}, 0.6, 0.1, 100.0));  // no sky
  RenderOptions o;
  o.width = 96;
  o.height = 54;
  o.method = Method::Deferred;
  Renderer& r = renderer(scene);
  o.camera = 1;
  const FrameStats& first = renderFrame(r, o);
  ASSERT_TRUE(passRan(first, "skybox"));
  ASSERT_EQ(first.skyPixels, 0);
  const std::vector<int> cameras = {0, 1, 1, 1, 0, 0, 0, 1, 0, 1, 1, 1};
  for (int camera : cameras) {
    o.camera = camera;
    submitFrame(r, o);
  }
  const std::vector<FrameStats> got = finishFrames(r);
  ASSERT_EQ(got.size(), cameras.size());
  // The model: the newest retired count (camera, sky visible), updated by frames that drew the skybox.
  int countedCamera = 1;
  bool countedSky = false;
  std::vector<bool> drew(cameras.size(), false);
  for (size_t i = 0; i < cameras.size(); ++i) {
    if (i >= kFrameSlots && drew[i - kFrameSlots]) {
      countedCamera = cameras[i - kFrameSlots];
      countedSky = cameras[i - kFrameSlots] == 0;
    }
    drew[i] = !(countedCamera == cameras[i] && !countedSky);
    EXPECT_EQ(passRan(got[i], "skybox"), drew[i]) << "frame " << i << " (camera " << cameras[i] << ")";
    if (passRan(got[i], "skybox")) EXPECT_EQ(got[i].skyPixels > 0, cameras[i] == 0) << "frame " << i;
  }
  // The last frame (camera 1, drawn or skipped) is the synchronous one.
  const std::vector<CpuImage> last = readBackLastFrame(r, {Target::Final});
  OwnRenderer fresh(scene);
  renderFrame(fresh.r, o, {{Target::Final}});
  EXPECT_EQ(differingTexels(last[0], fresh.r.readback[size_t(Target::Final)]), 0u);
}

// Frames in flight back to back, with every buffer the GPU alone writes and reads again each
// frame in use (clustered lists, light setup's scratch, fairy bins); then a synchronous frame,
// which finishes them first and keeps their statistics for finishFrames.
TEST_F(GpuTest, ASynchronousFrameFinishesTheFramesInFlight) {
  Scene scene = builtinTemple(64);
  RenderOptions o;
  o.width = 64;
  o.height = 36;
  o.method = Method::Clustered;
  o.lightSetup = ctx().features.float64 ? LightSetup::Gpu : LightSetup::Cpu;
  o.fairySplat = FairySplat::Compute;
  o.fairies = true;
  Renderer& r = renderer(scene);
  for (int i = 0; i < 4; ++i) {
    o.time = 0.25 * i;
    submitFrame(r, o);
  }
  const FrameStats& st = renderFrame(r, o, {{Target::Final}});
  EXPECT_GT(st.frameMs, 0.0);
  EXPECT_FALSE(r.readback[size_t(Target::Final)].empty());
  const std::vector<FrameStats> earlier = finishFrames(r);
  EXPECT_EQ(earlier.size(), 4u);
  EXPECT_TRUE(finishFrames(r).empty());
}

}  // namespace gb
