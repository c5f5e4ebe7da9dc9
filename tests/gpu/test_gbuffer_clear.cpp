// The G-buffer cleared in compute (clear_gbuffer, --gbuffer-clear compute) leaves every target
// bit for bit as the render pass's clear does, also where the previous frame drew geometry that
// this one does not: the stale texels must be zeroed, not loaded. Under --gbuffer visibility the
// cleared target is the visibility id (0: no geometry), which gbuffer_resolve reads.
#include "renderer/core/camera.h"
#include "renderer/scene/builtin.h"
#include "tests/gpu/gpu_test.h"

namespace gb {

TEST_F(GpuTest, ComputeClearsLeaveTheGBufferAsTheRenderPassClearDoes) {
  Scene scene = builtinTemple(16);
  // Camera 1 looks straight down at the temple's floor: geometry in every pixel.
  scene.cameras.push_back(lookAtCamera("down", {0.0, 3.0, 0.0}, {0.0, 0.0, 0.001}, 0.6, 0.1, 100.0));
  RenderOptions o;
  o.width = 96;
  o.height = 54;
  o.lights = 16;
  o.primitiveId = true;               // a 4-byte uint target
  o.position = PositionSource::Rgba32f;  // a 16-byte float target
  struct Case {
    Method method;
    GBufferKind gbuffer;
  };
  for (const Case k : {Case{Method::Deferred, GBufferKind::Raster}, Case{Method::Clustered, GBufferKind::Raster},
                       Case{Method::Clustered, GBufferKind::Visibility}}) {
    const Method m = k.method;
    std::vector<Target> targets = {Target::AlbedoSpecular, Target::NormalShadow, Target::Depth,
                                   Target::Position,       Target::Hdr,          Target::Final};
    if (k.gbuffer == GBufferKind::Visibility) targets.push_back(Target::Visibility);
    o.method = m;
    o.gbuffer = k.gbuffer;
    o.camera = 0;
    o.gbufferClear = GBufferClear::RenderPass;
    EXPECT_FALSE(passRan(render(scene, o, {targets}), "clear_gbuffer"));
    std::vector<CpuImage> expected;
    for (Target t : targets) expected.push_back(renderer(scene).readback[size_t(t)]);
    o.gbufferClear = GBufferClear::Compute;
    o.camera = 1;
    render(scene, o, {{Target::Depth}});
    const CpuImage& full = renderer(scene).readback[size_t(Target::Depth)];
    for (uint32_t y = 0; y < o.height; ++y)
      for (uint32_t x = 0; x < o.width; ++x) ASSERT_GT(full.value(x, y, 0), 0.0) << "camera 1 sees geometry everywhere";
    o.camera = 0;
    const FrameStats& st = render(scene, o, {targets});
    EXPECT_TRUE(passRan(st, "clear_gbuffer")) << name(m);
    EXPECT_EQ(passRan(st, "visibility"), k.gbuffer == GBufferKind::Visibility) << name(m);
    size_t sky = 0;
    for (size_t i = 0; i < targets.size(); ++i) {
      const CpuImage& got = renderer(scene).readback[size_t(targets[i])];
      ASSERT_EQ(got.width, expected[i].width);
      for (uint32_t y = 0; y < got.height; ++y)
        for (uint32_t x = 0; x < got.width; ++x) {
          if (i == 0 && expected[2].value(x, y, 0) == 0.0) ++sky;
          for (uint32_t c = 0; c < got.channelCount(); ++c)
            ASSERT_EQ(got.raw(x, y, c), expected[i].raw(x, y, c))
                << name(m) << " " << targetName(targets[i]) << " " << x << "," << y << " channel " << c;
        }
    }
    EXPECT_GT(sky, 300u) << "camera 0 sees the sky, where camera 1's geometry must be cleared";
  }
}

}  // namespace gb
