// The GUI fixtures that also need gblens's device in the test (GpuTest: the frame the viewer should
// show, computed apart) and an Xvfb session (gui::Session): skipped without Xvfb, a folder per test.
#pragma once
#include "tests/support/test_paths.h"
#include <gtest/gtest.h>

#include <functional>
#include <string>
#include <vector>

#include "tests/gpu/gpu_test.h"
#include "tests/gui/gui_util.h"

namespace gb {

class GpuGuiTest : public GpuTest, protected gui::Session {
 protected:
  // The test's folder is GBLENS_BUILD_DIR/<prefix><test name> (Session::openTestDisplay).
  virtual std::string folderPrefix() const = 0;
  void SetUp() override {
    if (!gui::haveTool("Xvfb")) GTEST_SKIP() << "Xvfb is not installed (apt-get install xvfb)";
    ASSERT_EQ(gui::missingTool(), "") << "is missing (debian-packages.txt lists it; run make deps)";
    GpuTest::SetUp();
    std::string error;
    ASSERT_TRUE(openTestDisplay(folderPrefix(), 1280, 720, error)) << error;
  }
  void TearDown() override {
    closeDisplay();
    if (!IsSkipped()) GpuTest::TearDown();
  }

  // Starts `gblens view ARGS --validate --window 1280x720 --event-log` and waits for its first frame
  // (its layout in firstLayout_); the window's id (xdotool) in wid_.
  void startViewer(std::vector<std::string> args) {
    args.insert(args.begin(), {GBLENS_BINARY, "view"});
    for (const char* a : {"--validate", "--window", "1280x720", "--event-log"}) args.push_back(a);
    args.push_back((dir_ / "events.jsonl").string());
    // The pointer off the views (Xvfb starts it at the screen's centre, over the pane): a hover mark
    // drawn in some screenshots of the pane and not in others would tell A from A.
    xdotool("mousemove 2 718");
    viewer_ = gui::spawn(args, {"DISPLAY=" + xvfb_.display}, (dir_ / "viewer.log").string());
    firstLayout_ = waitEvent([](const nlohmann::json& j) { return j["event"] == "layout"; }, 60.0);
    ASSERT_FALSE(waitEvent([](const nlohmann::json& j) { return j["event"] == "ready"; }).is_null())
        << "the viewer did not present a frame; see " << (dir_ / "viewer.log");
    wid_ = xdotool("search --onlyvisible --name '^gblens'");
    wid_ = wid_.substr(0, wid_.find('\n'));
    ASSERT_FALSE(wid_.empty());
    xdotool("mousemove --window " + wid_ + " 640 715");  // the pointer on the status bar, off the views
  }
  // Quits with ctrl+Q: exit status 0 (no validation message).
  void quit() {
    xdotool("key --window " + wid_ + " ctrl+q");
    int status = -1;
    ASSERT_TRUE(gui::waitExit(viewer_, 30.0, status)) << "the viewer did not quit";
    viewer_ = -1;
    EXPECT_EQ(status, 0) << "validation messages or a failure; see " << (dir_ / "viewer.log");
  }
  // The first event of the whole log that `pred` accepts (whenever it came).
  nlohmann::json findEvent(const std::function<bool(const nlohmann::json&)>& pred, double seconds = 30.0) {
    size_t cursor = 0;
    return gui::waitForLine((dir_ / "events.jsonl").string(), seconds, pred, cursor);
  }
  std::string wid_;
  nlohmann::json firstLayout_;
};

}  // namespace gb
