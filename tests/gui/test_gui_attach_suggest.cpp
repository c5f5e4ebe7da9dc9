// attach --suggest without a layout, in the viewer as a person uses it (Xvfb, xdotool): the stream of
// the independent test subject tests/subjects/foreign_deferred is decoded with the layout gblens
// drafts; its views are the draft's quantities, the hover reads the app's own texels (its --dump of
// the frozen frame) under the draft's names, and ctrl+S saves the draft the viewer shows.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "tests/gui/attach_session.h"

namespace gb {

namespace fs = std::filesystem;
using nlohmann::json;
using attach_gui::readFile;

// attach --suggest without a layout: the viewer opens on the stream decoded with the drafted layout
// (its views are the draft's quantities), hover shows the app's own texels under the draft's names,
// and ctrl+S saves the draft the window shows into the working directory.
TEST_F(GuiAttachTest, SuggestWithoutALayoutStreamsUnderTheDraftAndSavesIt) {
  startViewer("--frames 16384", "--suggest");
  size_t fromStart = 0;  // logged as the window opened
  const json suggestion = gui::waitForLine((dir_ / "events.jsonl").string(), 10.0,
                                           [](const json& j) { return j["event"] == "attach_suggestion"; }, fromStart);
  ASSERT_FALSE(suggestion.is_null());
  EXPECT_EQ(suggestion["streamed"], true);
  const json draft = suggestion["draft"];
  std::vector<std::string> declared, shown;
  for (const json& t : draft["targets"])
    for (const json& q : t["quantities"]) declared.push_back(q["name"]);
  ASSERT_FALSE(waitEvent([](const json& j) { return j["event"] == "attach_frame" && j["received"] >= 2; }).is_null());
  xdotool("key --window " + wid_ + " 1");
  const json grid = waitEvent([](const json& j) { return j["event"] == "layout" && j["views"].size() > 1; });
  ASSERT_FALSE(grid.is_null());
  json occlusionView;
  for (const json& v : grid["views"]) {
    shown.push_back(v["view"]);
    EXPECT_FALSE(v.contains("unavailable")) << v.dump();
    if (v["view"] == "occlusion") occlusionView = v;
  }
  std::sort(shown.begin(), shown.end());
  std::sort(declared.begin(), declared.end());
  EXPECT_EQ(shown, declared);
  ASSERT_FALSE(occlusionView.is_null()) << "the draft guessed no occlusion:\n" << draft.dump(2);

  // Paused on a frame, the hover over the occlusion view reads the app's own r8 texel of that frame.
  xdotool("key --window " + wid_ + " space");
  const json paused = waitEvent([](const json& j) { return j["event"] == "attach_state" && j["state"] == "paused"; });
  ASSERT_FALSE(paused.is_null());
  const uint64_t frozen = paused["app_frame"];
  const fs::path dump = dir_ / "dump";
  const json cam = dumpAppFrame(frozen);
  ASSERT_FALSE(cam.is_null());
  const uint32_t width = cam["width"], height = cam["height"];
  const std::string occlusion = readFile(dump / "occlusion.bin");
  ASSERT_EQ(occlusion.size(), size_t(width) * height);
  // A screen point over the occlusion view (shrunk: a screen pixel spans more than one texel, so the
  // texel is the one the hover names, checked to be under that point).
  const double scale = occlusionView["scale"];
  const double sx = double(occlusionView["origin"][0]) + width / 3.0 * scale;
  const double sy = double(occlusionView["origin"][1]) + height * 3.0 / 4.0 * scale;
  xdotool("mousemove --window " + wid_ + " " + std::to_string(int(sx)) + " " + std::to_string(int(sy)));
  const json hover = waitEvent([&](const json& j) { return j["event"] == "hover" && j["view"] == "occlusion"; });
  ASSERT_FALSE(hover.is_null()) << "no hover text over the occlusion view";
  unsigned px = 0, py = 0;
  ASSERT_EQ(std::sscanf(hover["text"].get<std::string>().c_str(), "occlusion (%u, %u)", &px, &py), 2) << hover["text"];
  EXPECT_LE(std::abs((px + 0.5) * scale - (int(sx) + 0.5 - double(occlusionView["origin"][0]))), scale + 1.0);
  EXPECT_LE(std::abs((py + 0.5) * scale - (int(sy) + 0.5 - double(occlusionView["origin"][1]))), scale + 1.0);
  ASSERT_TRUE(px < width && py < height);
  const std::string prefix = "occlusion (" + std::to_string(px) + ", " + std::to_string(py) + ")";
  const std::string stored = prefix + "  stored occlusion (r8_unorm) occlusion " +
                             std::to_string(uint8_t(occlusion[size_t(py) * width + px]));
  EXPECT_EQ(hover["text"].get<std::string>().rfind(stored, 0), 0u) << hover["text"] << "\nexpected to start with " << stored;

  // ctrl+S: the draft the stream is decoded with, saved where gblens runs.
  xdotool("key --window " + wid_ + " ctrl+s");
  const json saved = waitEvent([](const json& j) { return j["event"] == "draft_saved"; });
  ASSERT_FALSE(saved.is_null());
  ASSERT_EQ(saved["status"].get<std::string>().rfind("saved ", 0), 0u) << saved["status"];
  EXPECT_EQ(json::parse(std::ifstream(dir_ / saved["path"].get<std::string>())), draft);
  gui::Screenshot shot;
  std::string error;
  ASSERT_TRUE(gui::screenshot(xvfb_.display, (dir_ / "suggest.png").string(), shot, error)) << error;

  xdotool("key --window " + wid_ + " ctrl+q");
  int viewerStatus = -1;
  ASSERT_TRUE(gui::waitExit(viewer_, 30.0, viewerStatus)) << "the viewer did not quit";
  viewer_ = -1;
  EXPECT_EQ(viewerStatus, 0) << "validation messages or a failure; see " << (dir_ / "viewer.log");
}


}  // namespace gb
