// The probe's track across a sequence (views/analysis/probe_track.h) on frames made up in memory: a
// camera moved along x over a plane facing it (tests/support planeFrame), so every point moves by the
// same, hand-computed number of pixels from frame to frame; the track must land on exactly those
// positions, stop where the point leaves the image, and decode the view at each texel it reaches.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <vector>

#include "views/analysis/probe_track.h"
#include "views/analysis/visualize.h"
#include "tests/support/capture_util.h"

namespace gb {

namespace {

constexpr uint32_t kW = 64, kH = 48;

// Where pixel centre px of a frame whose camera is at x = from lies in one whose camera is at x = to,
// worked out by hand: the point's eye x is ndc * depth / P00 (P00 = clipFromEye[0][0]), its world x
// that plus the camera's x; the other camera sees it at world x - to.
double movedX(double px, double from, double to) {
  const double p00 = planeFrame(kW, kH, 0.0).camera.clipFromEye[0][0];
  const double ndc = 2.0 * px / kW - 1.0;
  const double world = from + ndc * kPlaneDepth / p00;
  return ((world - to) * p00 / kPlaneDepth + 1.0) * kW / 2.0;
}

struct Frames {
  std::vector<double> cameraX;
  std::vector<std::shared_ptr<const FrameSnapshot>> frames;
  explicit Frames(std::vector<double> xs) : cameraX(std::move(xs)) {
    for (size_t i = 0; i < cameraX.size(); ++i)
      frames.push_back(std::make_shared<FrameSnapshot>(planeFrame(kW, kH, cameraX[i], 0.6 + 0.2 * double(i))));
  }
  TrackFrames source() const {
    return [this](size_t i) { return i < frames.size() ? frames[i] : nullptr; };
  }
};

ViewDef finalView(const FrameSnapshot& f) {
  const std::vector<ViewDef> views = layoutViews(f.layout);
  return views[size_t(findView(views, "final"))];
}

}  // namespace

// Three frames, the camera 0.2 units further right each time (2.27 pixels of 64 at this field of view
// and depth: not a whole number, so the sub-texel position is checked too).
TEST(ProbeTrack, FollowsAPointThroughACameraTranslation) {
  const Frames seq({0.0, 0.2, 0.4});
  const glm::ivec2 probed(30, 20);
  const ProbeTrack t = trackProbe(3, seq.source(), 1, probed, finalView(*seq.frames[0]));
  ASSERT_EQ(t.first, 0u);
  ASSERT_EQ(t.last, 2u);
  EXPECT_EQ(t.stopBefore, "");
  EXPECT_EQ(t.stopAfter, "");
  for (size_t i = 0; i < 3; ++i) {
    const double x = movedX(probed.x + 0.5, seq.cameraX[1], seq.cameraX[i]);
    ASSERT_TRUE(t.positions[i]) << i;
    EXPECT_NEAR(t.positions[i]->x, x, 1e-6) << "frame " << i;
    EXPECT_NEAR(t.positions[i]->y, probed.y + 0.5, 1e-6) << "frame " << i;
    EXPECT_EQ(*t.texels[i], glm::ivec2(int(std::floor(x)), probed.y)) << "frame " << i;
  }
  // The hand-computed texels: 2.27 pixels a frame to the left as the camera goes right.
  EXPECT_EQ(*t.texels[0], glm::ivec2(32, 20));
  EXPECT_EQ(*t.texels[2], glm::ivec2(28, 20));
  // The values plotted are the view's at those texels, in each frame (brighter frame by frame).
  const ViewDef view = finalView(*seq.frames[0]);
  ASSERT_EQ(t.values.size(), size_t(view.components));
  for (size_t i = 0; i < 3; ++i) {
    const auto value = viewValue(*seq.frames[i], view, uint32_t(t.texels[i]->x), uint32_t(t.texels[i]->y));
    ASSERT_TRUE(value);
    for (size_t c = 0; c < t.values.size(); ++c) EXPECT_EQ(t.values[c][i], (*value)[c]) << "frame " << i << " component " << c;
  }
  EXPECT_LT(t.values[0][0], t.values[0][2]) << "the frames get brighter";
  const nlohmann::json j = trackJson(t);
  EXPECT_EQ(j["texels"][2], nlohmann::json::array({28, 20}));
}

// A point near the left edge: followed back (it moves right, into the image), lost going forward.
TEST(ProbeTrack, StopsWhereThePointLeavesTheImage) {
  const Frames seq({0.0, 0.2, 0.4, 0.6});
  const ProbeTrack t = trackProbe(4, seq.source(), 1, {1, 10}, finalView(*seq.frames[0]));
  EXPECT_EQ(t.first, 0u);
  EXPECT_EQ(t.last, 1u);
  EXPECT_NE(t.stopAfter.find("leaves the image"), std::string::npos) << t.stopAfter;
  EXPECT_FALSE(t.texels[2]);
  EXPECT_FALSE(t.texels[3]);
  EXPECT_TRUE(std::isnan(t.values[0][2]));
  EXPECT_EQ(*t.texels[0], glm::ivec2(int(std::floor(movedX(1.5, 0.2, 0.0))), 10));
}

// A frame that cannot be loaded ends the track there; the probed frame alone is still a track.
TEST(ProbeTrack, StopsAtAFrameThatCannotBeLoaded) {
  const Frames seq({0.0, 0.2});
  const TrackFrames missing = [&](size_t i) { return i == 0 ? nullptr : seq.frames[i]; };
  const ProbeTrack t = trackProbe(2, missing, 1, {30, 20}, finalView(*seq.frames[1]));
  EXPECT_EQ(t.first, 1u);
  EXPECT_EQ(t.last, 1u);
  EXPECT_NE(t.stopBefore.find("could not be loaded"), std::string::npos) << t.stopBefore;
}

}  // namespace gb

namespace gb {

// The same frames rendered with jitter: frame i shows at p the point whose unjittered place is p - j_i,
// and another frame shows it at its unjittered place + its own jitter (frame 2's is not known: none).
TEST(ProbeTrack, TakesEachFramesJitterOutAndPutsTheNextOnesIn) {
  const Frames seq({0.0, 0.2, 0.4});
  const std::vector<std::optional<glm::dvec2>> jitter = {glm::dvec2(0.25, 0.125), glm::dvec2(-0.375, 0.25), std::nullopt};
  const TrackJitters jitters = [&](size_t i) { return jitter[i]; };
  const glm::ivec2 probed(30, 20);
  const ProbeTrack t = trackProbe(3, seq.source(), 1, probed, finalView(*seq.frames[0]), jitters);
  ASSERT_EQ(t.first, 0u);
  ASSERT_EQ(t.last, 2u);
  const double x1 = 30.5, y1 = 20.5;  // the probed texel's centre, as frame 1 shows it
  const double u1 = x1 - jitter[1]->x, v1 = y1 - jitter[1]->y;  // its unjittered place in frame 1
  EXPECT_NEAR(t.positions[0]->x, movedX(u1, 0.2, 0.0) + jitter[0]->x, 1e-9);
  EXPECT_NEAR(t.positions[0]->y, v1 + jitter[0]->y, 1e-9);  // the camera moves along x only
  EXPECT_NEAR(t.positions[2]->x, movedX(u1, 0.2, 0.4), 1e-9);
  EXPECT_NEAR(t.positions[2]->y, v1, 1e-9);
}

}  // namespace gb
