// The motion check and flicker as views of a sequence's frame (issue 38), as a person uses them, under
// an Xvfb of the test's own with xdotool: tests/subjects/motion_rig's frames with a flipped y (its
// `--bug y_flipped`, imported with its layout), stepped to frame 2; the strip's verdict names the
// flipped y, V shows the "Motion error" view, the error hovered at a pixel is the one `gblens motion -o`
// wrote there (an independent path: the CLI's EXR), V again the "Motion class" view with its classes
// named, F the flicker of the view shown. Screenshots stay in the test's folder (gui_test/<test name>/:
// motion_error.png, probe_track.png, motion_class.png, grid_with_flicker.png).
#include "tests/support/test_paths.h"
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include "tests/gui/gpu_session.h"
#include "tests/support/capture_util.h"
#include "views/capture/exr.h"

namespace gb {
namespace {

using json = nlohmann::json;

class GuiMotionTest : public GpuGuiTest {
 protected:
  std::string folderPrefix() const override { return "gui_test/"; }
  // The rig's five frames (160x96) with `bug`, imported as a sequence (frames 0..4).
  std::string rigSequence(const std::string& bug) {
    const std::string rig = GBLENS_BUILD_DIR + "/tests/subjects/motion_rig/motion_rig";
    const std::string frames = (dir_ / "frames").string();
    RunResult r = runShell("'" + rig + "' --out '" + frames + "' --frames 5 --bug " + bug);
    EXPECT_EQ(r.exitCode, 0) << r.output;
    std::filesystem::copy_file(GBLENS_SOURCE_DIR + "/tests/subjects/motion_rig/layout.json", frames + "/layout.json");
    r = runGblens("import --layout '" + frames + "/layout.json' --frames 0..4 -o '" + (dir_ / "seq").string() + "'");
    EXPECT_EQ(r.exitCode, 0) << r.output;
    return (dir_ / "seq").string();
  }
  glm::ivec2 screenOf(const json& view, double x, double y) {
    return {int(double(view["origin"][0]) + x * double(view["scale"])), int(double(view["origin"][1]) + y * double(view["scale"]))};
  }
  void moveTo(glm::ivec2 p, const std::string& then = "") {
    xdotool("mousemove --window " + wid_ + " " + std::to_string(p.x) + " " + std::to_string(p.y) + then);
  }
  json waitLayoutOf(const std::string& view) {
    return waitEvent([&](const json& j) {
      return j["event"] == "layout" && !j["views"].empty() && j["views"][0]["view"] == view && !j["views"][0].contains("unavailable");
    });
  }
  json waitHover(const std::string& view) {
    return waitEvent([&](const json& j) { return j["event"] == "hover" && j["view"] == view; });
  }
  void shot(const std::string& name) {
    std::this_thread::sleep_for(std::chrono::milliseconds(700));  // the frame logged is on screen
    gui::Screenshot s;
    std::string error;
    ASSERT_TRUE(gui::screenshot(xvfb_.display, (dir_ / name).string(), s, error)) << error;
  }
};

// The number after "NAME: " in a hover text.
double hoverNumber(const json& hover, const std::string& name) {
  const std::string text = hover["text"].get<std::string>();
  return std::stod(text.substr(text.find(name + ": ") + name.size() + 2));
}

}  // namespace

TEST_F(GuiMotionTest, TheMotionCheckAndFlickerAreViewsOfTheFrameShown) {
  const std::string seq = rigSequence("y_flipped");
  // The CLI's answer first: pair 1 -> 2's error and class maps.
  const RunResult cli = runGblens("motion '" + seq + "' -o '" + (dir_ / "motion").string() + "'");
  ASSERT_EQ(cli.exitCode, 1) << cli.output;
  CpuImage pair;  // as gblens motion -o writes it: "motion.error", "motion.class" (f32), the rig's 160x96
  pair.name = "motion", pair.type = PixelType::F32, pair.channels = {"error", "class"}, pair.width = 160, pair.height = 96;
  std::string error;
  ASSERT_TRUE(readExr((dir_ / "motion" / "pair_0002.exr").string(), pair, error)) << error;
  const int ce = 0, cc = 1;
  // A pixel on a surface with a clear error (away from the image's edges): the first of the middle row.
  glm::ivec2 px(-1);
  for (uint32_t x = 20; x + 20 < pair.width && px.x < 0; ++x)
    if (std::isfinite(pair.value(x, pair.height / 2, uint32_t(ce))) && pair.value(x, pair.height / 2, uint32_t(ce)) > 0.5)
      px = glm::ivec2(int(x), int(pair.height / 2));
  ASSERT_GE(px.x, 0) << "no surface pixel with an error in the middle row";
  const double cliError = pair.value(uint32_t(px.x), uint32_t(px.y), uint32_t(ce));
  const int cliClass = int(pair.value(uint32_t(px.x), uint32_t(px.y), uint32_t(cc)));

  startViewer({seq});
  // Frame 0 has no previous frame; `.` twice: frame 2, whose pair 1 -> 2 is checked in the worker.
  xdotool("key --window " + wid_ + " period period");
  const json pairEvent = waitEvent([](const json& j) { return j["event"] == "motion_pair" && j["index"] == 2; }, 60.0);
  ASSERT_FALSE(pairEvent.is_null()) << "no motion check of frame 2";
  const std::string line = pairEvent["line"].get<std::string>();
  EXPECT_NE(line.find("y is flipped (+y points up)"), std::string::npos) << line;
  EXPECT_NE(line.find("1 -> 2"), std::string::npos) << line;
  // The pair as the CLI judged it: the same detected convention (its lag decided: frame 0 was given
  // as N-2) and the same pixel counts.
  std::ifstream in(dir_ / "motion" / "motion.json");
  const json report = json::parse(in);
  ASSERT_EQ(report["pairs"][1]["current"], 2);
  EXPECT_EQ(pairEvent["pair"]["detected"], report["pairs"][1]["detected"]) << pairEvent.dump();
  EXPECT_EQ(pairEvent["pair"]["detected"]["lag"], 0) << "pair 1 -> 2 was not given frame 0";
  EXPECT_EQ(pairEvent["pair"]["pixels"], report["pairs"][1]["pixels"]);

  // V: the Motion error view alone; the error under the mouse is the CLI's at that pixel.
  xdotool("key --window " + wid_ + " v");
  const json errorView = waitLayoutOf("Motion error");
  ASSERT_FALSE(errorView.is_null()) << "V did not show the Motion error view";
  const glm::ivec2 at = screenOf(errorView["views"][0], px.x + 0.5, px.y + 0.5);
  moveTo(at);
  const json hover = waitHover("Motion error");
  ASSERT_FALSE(hover.is_null()) << "no hover over the Motion error view";
  EXPECT_EQ(float(hoverNumber(hover, "Motion error")), float(cliError)) << hover["text"];  // %.9g: the float exactly
  shot("motion_error.png");

  // A click probes the pixel: the Pixel panel's "Across frames" plots the point's values over time.
  moveTo(at, " click 1");
  const json track = waitEvent([](const json& j) { return j["event"] == "track"; });
  ASSERT_FALSE(track.is_null()) << "the click made no track";
  EXPECT_EQ(track["pixel"], json::array({px.x, px.y}));
  moveTo({640, 715});
  shot("probe_track.png");

  // V again: the class view; its hover names the class the CLI wrote there.
  xdotool("key --window " + wid_ + " v");
  ASSERT_FALSE(waitLayoutOf("Motion class").is_null()) << "V again did not show the Motion class view";
  moveTo(at);
  const json classHover = waitHover("Motion class");
  ASSERT_FALSE(classHover.is_null());
  EXPECT_EQ(int(hoverNumber(classHover, "Motion class")), cliClass) << classHover["text"];
  static const char* const kNames[] = {"none", "static", "moving", "disoccluded", "wrong"};
  EXPECT_NE(classHover["text"].get<std::string>().find(std::string("(") + kNames[cliClass] + ":"), std::string::npos)
      << classHover["text"];
  moveTo({640, 715});
  shot("motion_class.png");

  // 0 then F: the flicker of the first colour view over the whole sequence, at frame 2's pixels.
  xdotool("key --window " + wid_ + " 0");
  xdotool("key --window " + wid_ + " f");
  const json flicker = waitEvent([](const json& j) { return j["event"] == "flicker"; }, 60.0);
  ASSERT_FALSE(flicker.is_null()) << "F ran no flicker";
  EXPECT_FALSE(flicker.contains("error")) << flicker.dump();
  EXPECT_EQ(flicker["reference"], 2);
  EXPECT_EQ(flicker["frames"], 5);
  xdotool("key --window " + wid_ + " 1");  // the grid: every view, the flicker's among them
  const json grid = waitEvent([](const json& j) {
    if (j["event"] != "layout") return false;
    for (const json& v : j["views"])
      if (v["view"] == "Flicker stddev") return !v.contains("unavailable");
    return false;
  });
  EXPECT_FALSE(grid.is_null()) << "the flicker's views are not in the grid";
  shot("grid_with_flicker.png");

  // V: the Motion error view again; zoomed in with the wheel, its texels print the error there.
  xdotool("key --window " + wid_ + " v");
  const json again = waitLayoutOf("Motion error");
  ASSERT_FALSE(again.is_null());
  moveTo(screenOf(again["views"][0], px.x + 0.5, px.y + 0.5));
  json values;
  for (int step = 0; step < 30 && values.is_null(); ++step) {
    xdotool("click --window " + wid_ + " 4");
    values = waitEvent([](const json& j) { return j["event"] == "texel_values" && j["view"] == "Motion error" && !j["texels"].empty(); }, 1.0);
  }
  ASSERT_FALSE(values.is_null()) << "no values in the Motion error view's texels after 30 wheel steps";
  char expected[32];
  std::snprintf(expected, sizeof expected, "%.4g", cliError);
  bool sawPixel = false;
  for (const json& t : values["texels"])
    if (t["texel"] == json::array({px.x, px.y})) {
      sawPixel = true;
      EXPECT_EQ(t["lines"], json::array({expected})) << t.dump();
    }
  EXPECT_TRUE(sawPixel) << "the texel under the mouse was not among those printed";
  shot("motion_error_zoomed.png");
  quit();
}

// The rig without a bug: the first frame's motion views say why they are empty, frame 1's pair agrees.
TEST_F(GuiMotionTest, ACorrectSequenceAgreesAndTheFirstFrameHasNoPairToCheck) {
  const std::string seq = rigSequence("none");
  startViewer({seq});
  xdotool("key --window " + wid_ + " v");
  const json first = waitEvent([](const json& j) {
    return j["event"] == "layout" && !j["views"].empty() && j["views"][0]["view"] == "Motion error" && j["views"][0].contains("unavailable");
  });
  ASSERT_FALSE(first.is_null()) << "V did not show the Motion error view on frame 0";
  EXPECT_NE(first["views"][0]["unavailable"].get<std::string>().find("no previous frame"), std::string::npos) << first.dump();
  xdotool("key --window " + wid_ + " period");
  const json pairEvent = waitEvent([](const json& j) { return j["event"] == "motion_pair" && j["index"] == 1; }, 60.0);
  ASSERT_FALSE(pairEvent.is_null()) << "no motion check of frame 1";
  EXPECT_NE(pairEvent["line"].get<std::string>().find("Motion 0 -> 1: agrees with the layout"), std::string::npos) << pairEvent["line"];
  EXPECT_TRUE(pairEvent["pair"]["differences"].empty()) << pairEvent.dump();
  EXPECT_FALSE(waitLayoutOf("Motion error").is_null()) << "the Motion error view did not show frame 1's map";
  quit();
}

}  // namespace gb
