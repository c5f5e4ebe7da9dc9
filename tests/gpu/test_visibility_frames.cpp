// --gbuffer visibility beyond the target-by-target comparison (test_visibility.cpp): the reference
// error of both paths, the id against primitive_id and the reference's ray cast, the resolve's
// variants (stored position, motion), refusals, every pixel written, frames in flight, frames that
// overlap (the visibility pass in a side submission).
#include <cmath>
#include <cstdlib>
#include <list>
#include <set>

#include "renderer/core/camera.h"
#include "renderer/core/visibility.h"
#include "renderer/passes/passes.h"
#include "renderer/readback/target_readback.h"
#include "renderer/reference/reference.h"
#include "renderer/scene/builtin.h"
#include "tests/gpu/gpu_test.h"
#include "tests/gpu/visibility_test.h"
#include "views/analysis/accuracy.h"

namespace gb {

class VisibilityFrames : public GpuTest {};

// The reference error (gblens error, views/analysis/error) of both paths: the visibility path
// within docs/accuracy.md's figures for the raster path (the eye depth's float placement bound
// 1e-6; normals, albedo, shadow and lighting no worse than the raster pass's by more than the
// stated margins).
TEST_F(VisibilityFrames, BothPathsMeetTheReferenceFigures) {
  const Scene scene = builtinTemple(16);
  ReferenceCache cache(scene);
  RenderOptions o = visibilityOptions();
  FrameError e[2];
  for (int v = 0; v < 2; ++v) {
    o.gbuffer = v ? GBufferKind::Visibility : GBufferKind::Raster;
    e[v] = measureFrame(source(scene), o, cache).error;
    std::printf("reference error, %s: normal max %.4g mean %.3g deg; albedo untextured max %.3g, textured mean %.3g "
                "/255; eye depth max %.3g relative, beyond placement max %.3g; shadow mismatch %.4g; hdr untextured "
                "p99 %.3g; lighting per contribution max %.3g; silhouettes %llu\n",
                name(o.gbuffer), e[v].normalDeg.max, e[v].normalDeg.mean, e[v].albedoUntextured.max,
                e[v].albedoTextured.mean, e[v].eyeDepthRelative.max, e[v].fromEyeDepthBeyondPlacement.max,
                e[v].shadow.fraction, e[v].hdrUntexturedOutsideBand.relative.p99, e[v].lighting.perContribution.max,
                (unsigned long long)e[v].silhouette);
  }
  const FrameError &raster = e[0], &vis = e[1];
  EXPECT_EQ(vis.surface, raster.surface);  // the same pixels on the reference's triangle
  EXPECT_EQ(vis.silhouette, raster.silhouette);
  EXPECT_LE(vis.fromEyeDepthBeyondPlacement.max, 1e-6);  // docs/accuracy.md, the eye-depth tail
  EXPECT_LE(vis.eyeDepthRelative.max, 1.5 * raster.eyeDepthRelative.max);
  EXPECT_LE(vis.normalDeg.max, 1.5 * raster.normalDeg.max);
  EXPECT_LE(vis.normalDeg.mean, 1.1 * raster.normalDeg.mean);
  EXPECT_LE(vis.albedoUntextured.max, raster.albedoUntextured.max);
  EXPECT_LE(vis.albedoTextured.mean, 1.1 * raster.albedoTextured.mean);
  EXPECT_LE(vis.shadow.fraction, raster.shadow.fraction + 0.001);
  EXPECT_LE(vis.hdrUntexturedOutsideBand.relative.p99, 1.1 * raster.hdrUntexturedOutsideBand.relative.p99);
  EXPECT_LE(vis.lighting.perContribution.max, lightingBoundPerContribution(o.accumFormat));
}

// The visibility id decodes (renderer/core/visibility.h) to the triangle the raster pass's
// primitive_id names at every pixel, and to the reference ray cast's hit at the image centre.
TEST_F(VisibilityFrames, TheIdDecodesToTheInstanceAndTriangleOfThePixel) {
  const Scene scene = builtinTemple(16);
  RenderOptions o = visibilityOptions();
  render(scene, o, {{Target::PrimitiveId}});
  const CpuImage ids = renderer(scene).readback[size_t(Target::PrimitiveId)];
  o.gbuffer = GBufferKind::Visibility;
  render(scene, o, {{Target::Visibility}});
  const Renderer& r = renderer(scene);
  const CpuImage& vis = r.readback[size_t(Target::Visibility)];
  ASSERT_EQ(vis.width, o.width);
  const std::vector<uint32_t> first = firstPrimitiveIds(scene);
  uint64_t surface = 0;
  for (uint32_t y = 0; y < o.height; ++y)
    for (uint32_t x = 0; x < o.width; ++x) {
      uint32_t draw = 0, triangle = 0;
      if (!unpackVisibility(r.visibilityPacking, vis.raw(x, y, 0), draw, triangle)) {
        ASSERT_EQ(ids.raw(x, y, 0), 0u) << x << "," << y;
        continue;
      }
      ++surface;
      ASSERT_LT(draw, scene.instances.size());
      ASSERT_LT(triangle, scene.meshes[scene.instances[draw].mesh].indexCount / 3);
      ASSERT_EQ(first[draw] + triangle, ids.raw(x, y, 0)) << x << "," << y;
    }
  EXPECT_GT(surface, 5000u);
  // The centre pixel against the reference's ray cast.
  ReferenceCache cache(scene);
  const reference::Frame& f = *cache.get(r.camera, o.time, kShadowBandTexels, o.shadowMapSize).frame;
  const uint32_t cx = o.width / 2, cy = o.height / 2;
  const reference::Surface& s = f.at(cx, cy);
  ASSERT_TRUE(s.hit);
  uint32_t draw = 0, triangle = 0;
  ASSERT_TRUE(unpackVisibility(r.visibilityPacking, vis.raw(cx, cy, 0), draw, triangle));
  EXPECT_EQ(draw, s.instance);
  EXPECT_EQ(triangle, s.triangle);
  EXPECT_EQ(vis.raw(cx, cy, 0), packVisibility(r.visibilityPacking, s.instance, s.triangle));
}

// The resolve's variants (stored position, motion) against the G-buffer pass's, under camera
// motion and jitter; and a frame the visibility path cannot run says why and rasterizes.
TEST_F(VisibilityFrames, StoredPositionAndMotionMatchAndRefusedFramesRasterize) {
  const Scene scene = builtinTemple(16);
  RenderOptions o = visibilityOptions();
  o.position = PositionSource::Rgba32f;
  o.motion = true;
  o.cameraMotion = CameraMotion::Orbit;
  o.jitter = Jitter::Halton;
  const std::vector<Target> targets = {Target::Position, Target::Motion, Target::Depth, Target::Hdr};
  render(scene, o, {targets});
  std::vector<CpuImage> raster;
  for (Target t : targets) raster.push_back(renderer(scene).readback[size_t(t)]);
  o.gbuffer = GBufferKind::Visibility;
  EXPECT_TRUE(passRan(render(scene, o, {targets}), "gbuffer_resolve"));
  const Renderer& r = renderer(scene);
  double position = 0.0, motion = 0.0;
  for (uint32_t y = 0; y < o.height; ++y)
    for (uint32_t x = 0; x < o.width; ++x) {
      const double depth = raster[2].value(x, y, 0);
      for (uint32_t c = 0; c < 4; ++c) {
        const double d = std::abs(raster[0].value(x, y, c) - r.readback[size_t(Target::Position)].value(x, y, c));
        if (depth > 0.0) position = std::max(position, d / depth);
        else ASSERT_EQ(d, 0.0);
      }
      for (uint32_t c = 0; c < 2; ++c)
        motion = std::max(motion, std::abs(raster[1].value(x, y, c) - r.readback[size_t(Target::Motion)].value(x, y, c)));
    }
  std::printf("visibility vs raster: stored position max %.3g of the eye depth, motion max %.3g px\n", position, motion);
  EXPECT_LE(position, 1e-5);  // as the eye depth: the snap times the change per pixel
  EXPECT_LE(motion, 2e-3);    // rg16f: 1/1024 px steps below 2 px, the same point within the snap

  RenderOptions single = visibilityOptions();
  single.gbuffer = GBufferKind::Visibility;
  single.path = Path::SinglePass;
  single.method = Method::Deferred;
  const FrameStats& st = render(scene, single);
  EXPECT_TRUE(passRan(st, "gbuffer"));
  for (const PassStat& p : st.passes)
    if (p.name == "gbuffer_resolve") EXPECT_NE(p.reason.find("two-pass path"), std::string::npos) << p.reason;
}


// gbuffer_resolve writes every pixel: where the previous frame drew and this one does not, the
// targets hold 0 as the raster pass's clear leaves them; and frames in flight (a burst, with
// synchronization validation between submissions) raise no hazard on the visibility target; the
// burst's steady state is bounded by its wall time and its frames' GPU work.
TEST_F(VisibilityFrames, EveryPixelIsWrittenAndFramesInFlightAreClean) {
  Scene scene = builtinTemple(16);
  scene.cameras.push_back(lookAtCamera("down", {0.0, 3.0, 0.0}, {0.0, 0.0, 0.001}, 0.6, 0.1, 100.0));
  RenderOptions o = visibilityOptions();
  o.gbuffer = GBufferKind::Visibility;
  o.camera = 1;  // geometry in every pixel
  render(scene, o, {{Target::Depth}});
  o.camera = 0;
  render(scene, o, {{Target::Depth, Target::AlbedoSpecular, Target::NormalShadow, Target::Visibility}});
  const Renderer& r = renderer(scene);
  uint64_t sky = 0;
  for (uint32_t y = 0; y < o.height; ++y)
    for (uint32_t x = 0; x < o.width; ++x) {
      if (r.readback[size_t(Target::Visibility)].raw(x, y, 0) != 0) continue;
      ++sky;
      ASSERT_EQ(r.readback[size_t(Target::Depth)].raw(x, y, 0), 0u) << x << "," << y;
      for (uint32_t c = 0; c < 4; ++c) {
        ASSERT_EQ(r.readback[size_t(Target::AlbedoSpecular)].raw(x, y, c), 0u);
        ASSERT_EQ(r.readback[size_t(Target::NormalShadow)].raw(x, y, c), 0u);
      }
    }
  EXPECT_GT(sky, 300u);
  for (Method m : {Method::Deferred, Method::Tiled, Method::Clustered}) {
    o.method = m;
    const FrameBurst burst = renderBurst(renderer(scene), o, 4);
    ASSERT_FALSE(burst.frames.empty()) << name(m);
    EXPECT_GE(burst.inFlight, 2) << name(m);
    for (const FrameStats& f : burst.frames) EXPECT_TRUE(passRan(f, "gbuffer_resolve")) << name(m);
    // The steady state (the GPU clock between the counted frames' ends) fits in the burst's wall
    // time, and on one queue frames end no closer than the GPU time of one frame's passes.
    if (!GpuTest::ctx().features.timestamps) continue;
    const double counted = double(burst.frames.size());
    EXPECT_LE(burst.steadyMs * (counted - 1.0), burst.msPerFrame * counted) << name(m);
    double leastPasses = 1e300;
    for (size_t k = 1; k < burst.frames.size(); ++k) {
      double sum = 0.0;
      for (const PassStat& p : burst.frames[k].passes) sum += p.skipped ? 0.0 : p.ms;
      leastPasses = std::min(leastPasses, sum);
    }
    EXPECT_GE(burst.steadyMs, 0.99 * leastPasses) << name(m);
  }
}

// Frames that overlap (GBLENS_OVERLAP=on, renderer/frame/side_queue.h; on lavapipe's one queue the
// visibility pass is submitted apart and runs first, under synchronization validation): a burst
// whose time changes every frame alternates the depth and id between the two slots' images, its
// passes tile its GPU time, and it ends on the frame a renderer that does not overlap draws for the
// last frame alone, bit for bit. Tiled and clustered frames overlap once the shadow map is drawn
// (the first frame draws it: a raster pass the compute queue cannot run); deferred frames, whose
// lighting is raster, never do, and say so.
TEST_F(VisibilityFrames, FramesThatOverlapEndOnTheFrameARendererInOrderDraws) {
  struct Overlap {  // the renderer reads GBLENS_OVERLAP when it is made
    Renderer r;
    Overlap(const Scene& scene, const char* mode) {
      setenv("GBLENS_OVERLAP", mode, 1);
      initRenderer(r, GpuTest::ctx(), scene);
      unsetenv("GBLENS_OVERLAP");
    }
    ~Overlap() { destroyRenderer(r); }
  };
  const Scene scene = builtinTemple(16);
  const std::vector<Target> targets = {Target::Final, Target::Hdr, Target::Depth, Target::DepthStencil, Target::Visibility};
  for (Method m : {Method::Deferred, Method::Tiled, Method::Clustered}) {
    RenderOptions o = visibilityOptions();
    o.gbuffer = GBufferKind::Visibility;
    o.method = m;
    o.tonemapPass = TonemapPass::Compute;  // raster on a CPU device by default
    o.fairySplat = FairySplat::Compute;
    o.clusterAssign = ClusterAssign::Gpu;
    Overlap on(scene, "on"), off(scene, "off");
    ASSERT_TRUE(on.r.overlapAllowed);
    ASSERT_FALSE(off.r.overlapAllowed);
    std::set<VkImage> depthImages, idImages;
    const int frames = 5;
    for (int i = 0; i < frames; ++i) {
      o.time = 1.0 + 0.5 * i;
      submitFrame(on.r, o);
      depthImages.insert(on.r.targets[size_t(Target::DepthStencil)].image.image);
      idImages.insert(on.r.targets[size_t(Target::Visibility)].image.image);
    }
    const std::vector<FrameStats> got = finishFrames(on.r);
    ASSERT_EQ(got.size(), size_t(frames)) << name(m);
    EXPECT_EQ(depthImages.size(), 2u) << name(m);
    EXPECT_EQ(idImages.size(), 2u) << name(m);
    for (size_t i = 0; i < got.size(); ++i) {
      const FrameStats& f = got[i];
      const char* raster = i == 0 ? "(shadow_map)" : m == Method::Deferred ? "(directional_light)" : nullptr;
      EXPECT_EQ(f.overlap, raster == nullptr) << name(m) << " frame " << i << ": " << f.overlapReason;
      if (raster) EXPECT_NE(f.overlapReason.find(raster), std::string::npos) << name(m) << " frame " << i << ": " << f.overlapReason;
      if (!ctx().features.timestamps) continue;
      double spans = 0.0;
      for (const PassStat& p : f.passes) {
        if (p.skipped) continue;
        EXPECT_GE(p.beforeMs, 0.0) << name(m) << " " << p.name;
        spans += p.beforeMs + p.ms;
      }
      EXPECT_NEAR(spans, f.gpuMs, 1e-6 * f.gpuMs + 1e-9) << name(m);
    }
    runAfterFrame(on.r, [&](FrameGraph& g) { addReadbackPass(g, on.r, targets); }, {});
    const FrameStats& alone = renderFrame(off.r, o, {targets});
    EXPECT_FALSE(alone.overlap);
    for (Target t : targets)
      EXPECT_EQ(differingTexels(unpackReadback(on.r, t), off.r.readback[size_t(t)]), 0u) << name(m) << ": " << targetName(t);
  }
}

}  // namespace gb
