// The G-buffer cleared in compute (clear_gbuffer, --gbuffer-clear compute) leaves every target
// bit for bit as the render pass's clear does, also where the previous frame drew geometry that
// this one does not: the stale texels must be zeroed, not loaded.
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
  const std::vector<Target> targets = {Target::AlbedoSpecular, Target::NormalShadow, Target::Depth,
                                       Target::Position,       Target::Hdr,          Target::Final};
  for (Method m : {Method::Deferred, Method::Clustered}) {
    o.method = m;
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
    EXPECT_TRUE(passRan(render(scene, o, {targets}), "clear_gbuffer")) << name(m);
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
