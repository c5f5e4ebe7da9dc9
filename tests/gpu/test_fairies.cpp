// Fairy sprites splatted in compute (--fairy-splat compute) give the image the raster pass draws:
// the same pixels changed, by the same amounts up to the rounding of the sprite's local
// coordinates, in the frames of two methods, with sprites of a pixel or two far away and large
// ones near the camera, in front of and behind geometry.
#include <cmath>

#include "renderer/scene/builtin.h"
#include "tests/gpu/gpu_test.h"

namespace gb {

namespace {

// hdr of the frame with fairies drawn, splatted, and without them.
struct Frames {
  CpuImage drawn, splatted, none;
};

Frames renderFairies(GpuTest& t, const Scene& scene, RenderOptions o) {
  Frames f;
  o.fairies = true;
  o.fairySplat = FairySplat::Raster;
  const FrameStats& a = t.render(scene, o, {{Target::Hdr}});
  EXPECT_TRUE(passRan(a, "fairy_lights"));
  f.drawn = t.renderer(scene).readback[size_t(Target::Hdr)];
  o.fairySplat = FairySplat::Compute;
  const FrameStats& b = t.render(scene, o, {{Target::Hdr}});
  EXPECT_TRUE(passRan(b, "fairy_splat") && !passRan(b, "fairy_lights"));
  f.splatted = t.renderer(scene).readback[size_t(Target::Hdr)];
  o.fairies = false;
  t.render(scene, o, {{Target::Hdr}});
  f.none = t.renderer(scene).readback[size_t(Target::Hdr)];
  return f;
}

// Every pixel's splatted value within 1% of the sprites' contribution there (drawn - none) of
// the drawn one, plus 1e-5 relative for the float sums; at least `sprites` pixels show a sprite.
void expectSameSprites(const Frames& f, int sprites, const std::string& what) {
  int shown = 0, bad = 0;
  double worst = 0.0;
  for (uint32_t y = 0; y < f.drawn.height; ++y)
    for (uint32_t x = 0; x < f.drawn.width; ++x)
      for (int c = 0; c < 4; ++c) {
        const double d = f.drawn.value(x, y, c), s = f.splatted.value(x, y, c), n = f.none.value(x, y, c);
        const double contribution = std::abs(d - n);
        if (c == 0 && contribution > 1e-4) ++shown;
        const double bound = 0.01 * contribution + 1e-5 * std::max(std::abs(d), 1.0);
        worst = std::max(worst, std::abs(s - d) / bound);
        bad += !(std::abs(s - d) <= bound);
      }
  EXPECT_EQ(bad, 0) << what << ": worst |splatted - drawn| / bound " << worst;
  EXPECT_GE(shown, sprites) << what << ": too few sprite pixels for the comparison to mean anything";
}

}  // namespace

TEST_F(GpuTest, FairiesSplattedInComputeMatchTheDrawnSprites) {
  RenderOptions o;
  o.width = 160;
  o.height = 90;
  const Scene temple = builtinTemple(256);  // many small sprites over geometry and sky
  for (Method m : {Method::Deferred, Method::Clustered}) {
    o.method = m;
    expectSameSprites(renderFairies(*this, temple, o), 60, std::string("temple ") + name(m));
  }
  // Sprites tens of pixels wide near the camera, in front of and behind geometry, one clipped by
  // the near plane.
  Scene near = floorScene(20.0);
  addBox(near, {-0.5f, 0.0f, -1.0f}, {0.5f, 1.0f, 0.0f});
  setCamera(near, {0.0, 1.0, 3.0}, {0.0, 0.5, 0.0}, 0.9, 0.1, 50.0);
  for (int i = 0; i < 12; ++i) {
    PointLightDesc l;
    l.center = {-1.5 + 0.3 * i, 0.3 + 0.12 * i, 2.6 - 0.35 * i};
    l.radius = 4.0;
    l.color = glm::vec3(1.0f, 0.5f + 0.04f * i, 0.3f);
    near.lights.push_back(l);
  }
  near.lights.push_back(near.lights.front());
  near.lights.back().center = {0.0, 1.0, 2.95};  // its sprite straddles the near plane's depth
  o.method = Method::Deferred;
  expectSameSprites(renderFairies(*this, near, o), 300, "near sprites");
  o.reversedZ = true;
  expectSameSprites(renderFairies(*this, near, o), 300, "near sprites, reversed z");
}

}  // namespace gb
