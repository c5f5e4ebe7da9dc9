// The built-in scene renders in every path/option combination with zero validation messages.
#include "renderer/scene/builtin.h"
#include "tests/gpu/gpu_test.h"

namespace gb {

TEST_F(GpuTest, TempleRendersInEveryPathAndDepthMode) {
  Scene scene = builtinTemple(64);
  for (Path path : {Path::TwoPass, Path::SinglePass})
    for (bool eyeDepth : {true, false}) {
      RenderOptions o;
      o.width = 160;
      o.height = 90;
      o.path = path;
      o.eyeDepth = eyeDepth;
      const FrameStats& st = render(scene, o, {{Target::Final}});
      EXPECT_GT(st.lightsVisible, 0u);
      const CpuImage& img = renderer(scene).readback[size_t(Target::Final)];
      ASSERT_EQ(img.width, 160u);
      double sum = 0;
      for (uint32_t y = 0; y < img.height; ++y)
        for (uint32_t x = 0; x < img.width; ++x) sum += img.value(x, y, 0) + img.value(x, y, 1) + img.value(x, y, 2);
      double mean = sum / (3.0 * img.width * img.height);
      EXPECT_GT(mean, 0.05) << name(path) << " eye depth " << eyeDepth;
      EXPECT_LT(mean, 0.9) << name(path) << " eye depth " << eyeDepth;
    }
}

}  // namespace gb
