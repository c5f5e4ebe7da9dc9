// The attach GUI tests' session (test_gui_attach*.cpp): Xvfb, the foreign_deferred test subject's
// layout with live sources and a camera sidecar, and `gblens attach` started in the test's folder.
#pragma once
#include "tests/support/test_paths.h"
#include <gtest/gtest.h>
#include <signal.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "tests/gui/gui_util.h"

namespace gb {

namespace fs = std::filesystem;
using nlohmann::json;

namespace attach_gui {

// Where each target of layout.json is live (the app's README: render pass in its command buffer,
// colour attachment or -1 for depth).
inline const std::map<std::string, std::pair<int, int>> kLive = {{"position", {0, 0}}, {"normal", {0, 1}},   {"albedo", {0, 2}},
                                                          {"depth", {0, -1}},   {"occlusion", {1, 0}}, {"hdr", {2, 0}},
                                                          {"final", {3, 0}}};

// layout.json with live sources; the camera from a sidecar (the app's uniform buffer has no name);
// the decoding fields today's gblens refuses left out (no source or stored texel changes).
inline json liveLayout(const std::string& sidecar) {
  json layout = json::parse(std::ifstream(FOREIGN_DEFERRED_DIR + "/layout.json"));
  for (json& t : layout["targets"]) {
    const auto [pass, color] = kLive.at(t["name"].get<std::string>());
    t["source"] = {{"live", color < 0 ? json{{"pass", pass}, {"depth", true}} : json{{"pass", pass}, {"color", color}}}};
    for (json& q : t["quantities"])
      if (q.value("quantity", "") == "depth") q.erase("scale");
  }
  layout["camera"].erase("renderdoc");
  layout["camera"].erase("up");
  layout["camera"]["sidecar"] = sidecar;
  return layout;
}

inline std::string readFile(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace attach_gui

class GuiAttachTest : public ::testing::Test, protected gui::Session {
 protected:
  void SetUp() override {
    using namespace attach_gui;
    if (!gui::haveTool("Xvfb")) GTEST_SKIP() << "Xvfb is not installed (apt-get install xvfb)";
    ASSERT_EQ(gui::missingTool(), "") << "is missing (debian-packages.txt lists it; run make deps)";
    std::string error;
    ASSERT_TRUE(openTestDisplay("gui_attach_", 1024, 640, error)) << error;
    // The camera of frame 0 (the app's own dump) as the sidecar: the views and texels do not use it.
    int status = 0;
    gui::run(std::string("'") + FOREIGN_DEFERRED_BINARY + "' --frames 1 --dump '" + (dir_ / "dump0").string() + "' 2>&1", &status);
    ASSERT_EQ(status, 0);
    const json cam = json::parse(std::ifstream(dir_ / "dump0" / "camera.json"));
    std::ofstream(dir_ / "camera.json") << json{{"view_from_world", cam["view_from_world"]}, {"clip_from_view", cam["clip_from_view"]}}.dump();
    std::ofstream(dir_ / "live.json") << liveLayout((dir_ / "camera.json").string()).dump(2);
  }
  void TearDown() override {
    closeDisplay();
    if (app_ > 0) kill(app_, SIGKILL);  // the application ran on after the viewer closed
  }
  // gblens attach in dir_ (the capture button writes into the working directory).
  void startViewer(const std::string& appArgs, const std::string& attachArgs = "--layout live.json") {
    const std::string command = "cd '" + dir_.string() + "' && exec '" + GBLENS_BINARY + "' attach " + attachArgs +
                                " --window 1024x640 --event-log events.jsonl --probe-log probe.jsonl -- '" +
                                FOREIGN_DEFERRED_BINARY + "' " + appArgs;
    viewer_ = gui::spawn({"sh", "-c", command}, {"DISPLAY=" + xvfb_.display}, (dir_ / "viewer.log").string());
    json open;
    for (int tries = 0; tries < 120 && open.is_null(); ++tries) {  // or gblens gave up (its log says why)
      int status = 0;
      if (gui::waitExit(viewer_, 0.0, status)) {
        viewer_ = -1;
        break;
      }
      open = waitEvent([](const json& j) { return j["event"] == "attach_open"; }, 0.5);
    }
    ASSERT_FALSE(open.is_null()) << "the viewer did not open on the stream; see " << (dir_ / "viewer.log");
    app_ = open["pid"].get<pid_t>();
    ASSERT_FALSE(waitEvent([](const json& j) { return j["event"] == "ready"; }).is_null());
    wid_ = xdotool("search --onlyvisible --name '^gblens'");
    wid_ = wid_.substr(0, wid_.find('\n'));
    ASSERT_FALSE(wid_.empty());
  }
  // Every event line so far.
  std::vector<json> events() {
    std::vector<json> out;
    std::ifstream in(dir_ / "events.jsonl");
    for (std::string line; std::getline(in, line);)
      if (!line.empty() && line.back() == '}') out.push_back(json::parse(line));
    return out;
  }
  // The app's own read-back of its frame `frame` (the same run without any layer, ending at that
  // frame: the app is deterministic) in dir_/dump; its camera.json (null, with a failure, if not).
  json dumpAppFrame(uint64_t frame) {
    int status = 0;
    gui::run(std::string("'") + FOREIGN_DEFERRED_BINARY + "' --frames " + std::to_string(frame + 1) + " --dump '" +
                 (dir_ / "dump").string() + "' 2>&1",
             &status);
    if (status != 0) {
      ADD_FAILURE() << "foreign_deferred --dump exited with " << status;
      return nullptr;
    }
    return json::parse(std::ifstream(dir_ / "dump" / "camera.json"));
  }

  pid_t app_ = -1;
  std::string wid_;
};

}  // namespace gb
