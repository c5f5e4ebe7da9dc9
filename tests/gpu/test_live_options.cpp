// The viewer changes options on one live renderer, frame after frame (headless commands never
// do): every combination of path, USE_EYE_DEPTH, LIGHT_STENCIL_CULLING and mask, in sequence and
// back, must render with zero validation messages (cached pipelines must match the render
// passes they are used in) and give the same image as a fresh renderer.
#include "renderer/scene/builtin.h"
#include "tests/gpu/gpu_test.h"

namespace gb {

TEST_F(GpuTest, OptionsChangeFrameToFrameOnOneRenderer) {
  Scene scene = builtinTemple(24);
  Scene fresh = builtinTemple(24);
  RenderOptions o;
  o.width = 64;
  o.height = 36;
  o.shadowMapSize = 128;
  int frames = 0;
  for (int pass = 0; pass < 2; ++pass)
    for (Path path : {Path::SinglePass, Path::TwoPass})
      for (bool eyeDepth : {true, false})
        for (bool culling : {true, false})
          for (StencilMask mask : {StencilMask::PerLight, StencilMask::Shared}) {
            if (!culling && mask == StencilMask::Shared) continue;
            o.path = path;
            o.eyeDepth = eyeDepth;
            o.stencilCulling = culling;
            o.stencilMask = mask;
            o.coverage = (frames % 3) == 0;
            render(scene, o, {{Target::Final}});
            ++frames;
            if (pass == 1) {  // the second round: the same pixels as a renderer that saw only this
              CpuImage live = renderer(scene).readback[size_t(Target::Final)];
              render(fresh, o, {{Target::Final}});
              EXPECT_EQ(live.data, renderer(fresh).readback[size_t(Target::Final)].data)
                  << name(path) << " eye depth " << eyeDepth << " culling " << culling << " " << name(mask);
            }
          }
  EXPECT_EQ(frames, 2 * 2 * 2 * 3);
}

}  // namespace gb
