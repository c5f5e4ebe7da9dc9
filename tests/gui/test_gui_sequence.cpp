// A sequence in the viewer (issue 38), as a person uses it, under an Xvfb of the test's own with
// xdotool: `gblens view SEQ@N` opens frame N with the timeline strip, a click probes a pixel and the
// probe follows its surface point through every frame (the hand-computed pixels of a camera moved
// along x over a plane), `.` and `,` step (the probe moves to the point's texel there), Space plays
// at the sequence's rate and wraps. The event log says which frame is shown; screenshots stay in the
// build tree (gui_test/TEST/) to look at: the strip, the plot over time, the followed texels.
#include "tests/support/test_paths.h"
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <string>
#include <thread>

#include "tests/gui/gpu_session.h"
#include "tests/support/capture_util.h"
#include "views/capture/sequence.h"

namespace gb {
namespace {

using json = nlohmann::json;

constexpr uint32_t kSequenceWidth = 192, kSequenceHeight = 108;
constexpr int kFrames = 10;
constexpr double kCameraStep = 0.2;  // the camera's move along x from frame to frame (5.1 pixels here)

class GuiSequenceTest : public GpuGuiTest {
 protected:
  std::string folderPrefix() const override { return "gui_test/"; }
  // Ten frames numbered 10..19 at 10 fps, each camera kCameraStep further right and each frame brighter:
  // more than the viewer keeps in memory (8).
  std::string writePlaneSequence() {
    const std::string dir = (dir_ / "seq").string();
    std::string error;
    const bool ok = writeSequence(
        dir, kFrames,
        [](size_t i, SequenceEntry& e, std::string&) {
          e.frame = planeFrame(kSequenceWidth, kSequenceHeight, kCameraStep * double(i), 0.45 + 0.06 * double(i));
          e.meta.scene = "test plane";
          e.meta.commandLine = "tests/gui/test_gui_sequence.cpp";
          e.number = 10 + int64_t(i);
          e.time = 0.1 * double(i);
          return true;
        },
        json::object(), error);
    EXPECT_TRUE(ok) << error;
    return dir;
  }
  void clickTexel(const json& view, double x, double y) {
    const int sx = int(double(view["origin"][0]) + x * double(view["scale"]));
    const int sy = int(double(view["origin"][1]) + y * double(view["scale"]));
    xdotool("mousemove --window " + wid_ + " " + std::to_string(sx) + " " + std::to_string(sy) + " click 1");
    xdotool("mousemove --window " + wid_ + " 640 715");
  }
  json waitFrame(int64_t number) {
    return waitEvent([&](const json& j) { return j["event"] == "sequence_frame" && j["frame"] == number; }, 30.0);
  }
  void shot(const std::string& name) {
    std::this_thread::sleep_for(std::chrono::milliseconds(700));  // the frame logged is on screen
    gui::Screenshot s;
    std::string error;
    ASSERT_TRUE(gui::screenshot(xvfb_.display, (dir_ / name).string(), s, error)) << error;
  }
};

// The texel pixel centre px of the frame with its camera at `from` moves to in the frame with its
// camera at `to`, worked out by hand (tests/unit/test_probe_track.cpp has the derivation).
int movedTexel(double px, double from, double to) {
  const double p00 = planeFrame(kSequenceWidth, kSequenceHeight, 0.0).camera.clipFromEye[0][0];
  const double world = from + (2.0 * px / kSequenceWidth - 1.0) * kPlaneDepth / p00;
  return int(std::floor(((world - to) * p00 / kPlaneDepth + 1.0) * kSequenceWidth / 2.0));
}

}  // namespace

TEST_F(GuiSequenceTest, TheTimelineStepsAndTheProbeFollowsItsSurfacePoint) {
  const std::string seq = writePlaneSequence();
  startViewer({seq + "@11"});
  const json opened = findEvent([](const json& j) { return j["event"] == "sequence_frame"; });
  ASSERT_FALSE(opened.is_null());
  EXPECT_EQ(opened["frame"], 11);
  EXPECT_EQ(opened["index"], 1);
  EXPECT_EQ(opened["frames"], kFrames);
  EXPECT_EQ(firstLayout_["views"][0]["image"], json::array({kSequenceWidth, kSequenceHeight}));

  // A click probes texel (96, 54) of frame 11: the track holds the point's texel in every frame.
  clickTexel(firstLayout_["views"][0], 96.5, 54.5);
  const json track = waitEvent([](const json& j) { return j["event"] == "track"; });
  ASSERT_FALSE(track.is_null()) << "the click made no track";
  EXPECT_EQ(track["pixel"], json::array({96, 54}));
  EXPECT_EQ(track["first"], 0);
  EXPECT_EQ(track["last"], kFrames - 1);
  for (int i = 0; i < kFrames; ++i)
    EXPECT_EQ(track["texels"][size_t(i)], json::array({movedTexel(96.5, kCameraStep, kCameraStep * i), 54})) << "frame index " << i;
  ASSERT_FALSE(track["values"].empty());
  EXPECT_EQ(track["view"], firstLayout_["views"][0]["view"]) << "the values plotted are the clicked view's";

  // `.`: frame 12, the probe on the point's texel there.
  xdotool("key --window " + wid_ + " period");
  json shown = waitFrame(12);
  ASSERT_FALSE(shown.is_null()) << "`.` did not show frame 12";
  EXPECT_EQ(shown["probe"], track["texels"][2]);
  EXPECT_NEAR(shown["time"].get<double>(), 0.2, 1e-9);
  EXPECT_EQ(shown["cached"], 8) << "the track read every frame; the cache keeps at most 8";
  shot("sequence_frame12.png");

  // `,` twice: frame 10; the probe there too.
  xdotool("key --window " + wid_ + " comma comma");
  shown = waitFrame(10);
  ASSERT_FALSE(shown.is_null()) << "`,` did not step back to frame 10";
  EXPECT_EQ(shown["probe"], track["texels"][0]);
  shot("sequence_frame10.png");

  // Space plays at 10 fps (the frames' times) and wraps to the first frame after the last; Space pauses.
  xdotool("key --window " + wid_ + " space");
  ASSERT_FALSE(waitFrame(19).is_null()) << "Space did not play";
  ASSERT_FALSE(waitFrame(10).is_null()) << "playing did not wrap to the first frame";
  xdotool("key --window " + wid_ + " space");
  quit();
}

// `gblens view SEQ` (no frame named) opens the first frame; a frame the sequence lacks is an error.
TEST_F(GuiSequenceTest, ASequenceOpensAtItsFirstFrameAndAMissingFrameIsRefused) {
  const std::string seq = writePlaneSequence();
  const RunResult missing = runGblens("view " + seq + "@7");
  EXPECT_EQ(missing.exitCode, 2) << missing.output;
  EXPECT_NE(missing.output.find("no frame 7"), std::string::npos) << missing.output;
  startViewer({seq});
  const json opened = findEvent([](const json& j) { return j["event"] == "sequence_frame"; });
  ASSERT_FALSE(opened.is_null());
  EXPECT_EQ(opened["frame"], 10);
  EXPECT_EQ(opened["index"], 0);
  quit();
}

}  // namespace gb
