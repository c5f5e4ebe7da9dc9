// The viewer on an attached application, as a person uses it: `gblens attach --layout L -- APP`
// under Xvfb, APP the independent test subject tests/subjects/foreign_deferred (another renderer:
// unnamed images, no labels, its layout's targets picked by render pass and attachment index). The
// grid shows exactly the layout's quantities; Space freezes the frame (no more frames taken, the
// application runs on); the hover text's stored codes and the capture written with C are the
// texels the application itself read back for that frame (its own --dump, run again without any
// layer: the app is deterministic); closing the viewer leaves the application running. A short run
// ends while attached: its last frame stays with "application exited (code 0)".
#include <gtest/gtest.h>
#include <signal.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <thread>

#include "tests/gui/gui_util.h"
#include "views/capture/capture.h"

namespace gb {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// Where each target of layout.json is live (the app's README: render pass in its command buffer,
// colour attachment or -1 for depth).
const std::map<std::string, std::pair<int, int>> kLive = {{"position", {0, 0}}, {"normal", {0, 1}},   {"albedo", {0, 2}},
                                                          {"depth", {0, -1}},   {"occlusion", {1, 0}}, {"hdr", {2, 0}},
                                                          {"final", {3, 0}}};

// layout.json with live sources; the camera from a sidecar (the app's uniform buffer has no name);
// the decoding fields today's gblens refuses left out (no source or stored texel changes).
json liveLayout(const std::string& sidecar) {
  json layout = json::parse(std::ifstream(FOREIGN_DEFERRED_DIR "/layout.json"));
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

std::string readFile(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace

class GuiAttachTest : public ::testing::Test, protected gui::Session {
 protected:
  void SetUp() override {
    if (!gui::haveTool("Xvfb")) GTEST_SKIP() << "Xvfb is not installed (apt-get install xvfb)";
    for (const char* tool : {"xdotool", "xwd", "convert"}) ASSERT_TRUE(gui::haveTool(tool)) << tool << " is missing";
    std::string error;
    ASSERT_TRUE(openDisplay(fs::path(GBLENS_BUILD_DIR) /
                                ("gui_attach_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name())),
                            1024, 640, error))
        << error;
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
                                " --window 1024x640 --event-log events.jsonl -- '" + FOREIGN_DEFERRED_BINARY + "' " + appArgs;
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

  pid_t app_ = -1;
  std::string wid_;
};

TEST_F(GuiAttachTest, TheStreamShowsTheLayoutsViewsPausesAndCapturesTheAppsOwnTexels) {
  startViewer("--frames 16384");  // minutes: it runs on while the test pauses, captures and closes
  // Live: frames keep coming.
  ASSERT_FALSE(waitEvent([](const json& j) { return j["event"] == "attach_frame" && j["received"] >= 3; }).is_null());

  // The grid: exactly the layout's quantities, all of them with something to show.
  xdotool("key --window " + wid_ + " 1");
  const json grid = waitEvent([](const json& j) { return j["event"] == "layout" && j["views"].size() > 1; });
  ASSERT_FALSE(grid.is_null());
  std::vector<std::string> shown, declared;
  json albedoView;
  for (const json& v : grid["views"]) {
    shown.push_back(v["view"]);
    EXPECT_FALSE(v.contains("unavailable")) << v.dump();
    if (v["view"] == "Albedo") albedoView = v;
  }
  const json layout = json::parse(std::ifstream(FOREIGN_DEFERRED_DIR "/layout.json"));
  for (const json& t : layout["targets"])
    for (const json& q : t["quantities"]) declared.push_back(q["name"]);
  std::sort(shown.begin(), shown.end());
  std::sort(declared.begin(), declared.end());
  EXPECT_EQ(shown, declared);
  ASSERT_FALSE(albedoView.is_null());

  // Pause: the frame shown is frozen, no frame is taken any more, the application runs on.
  xdotool("key --window " + wid_ + " space");
  const json paused = waitEvent([](const json& j) { return j["event"] == "attach_state" && j["state"] == "paused"; });
  ASSERT_FALSE(paused.is_null());
  const uint64_t frozen = paused["app_frame"];
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));
  const std::vector<json> all = events();
  for (size_t i = eventCursor_; i < all.size(); ++i) EXPECT_NE(all[i]["event"], "attach_frame") << "a frame was taken while paused";
  EXPECT_EQ(kill(app_, 0), 0) << "the application stopped while the viewer was paused";

  // The app's own read-back of that frame: the same run without any layer, ending at that frame.
  const fs::path dump = dir_ / "dump";
  int status = 0;
  gui::run(std::string("'") + FOREIGN_DEFERRED_BINARY + "' --frames " + std::to_string(frozen + 1) + " --dump '" +
               dump.string() + "' 2>&1",
           &status);
  ASSERT_EQ(status, 0);
  const json cam = json::parse(std::ifstream(dump / "camera.json"));
  const uint32_t width = cam["width"], height = cam["height"];
  const std::string albedo = readFile(dump / "albedo.bin");
  ASSERT_EQ(albedo.size(), size_t(width) * height * 4);

  // Hover over a texel of the albedo view: the stored codes are those the app wrote.
  const uint32_t px = width / 2, py = height * 2 / 3;
  const double sx = double(albedoView["origin"][0]) + (px + 0.5) * double(albedoView["scale"]);
  const double sy = double(albedoView["origin"][1]) + (py + 0.5) * double(albedoView["scale"]);
  xdotool("mousemove --window " + wid_ + " " + std::to_string(int(sx)) + " " + std::to_string(int(sy)));
  const std::string prefix = "Albedo (" + std::to_string(px) + ", " + std::to_string(py) + ")";
  const json hover = waitEvent([&](const json& j) { return j["event"] == "hover" && j["text"].get<std::string>().rfind(prefix, 0) == 0; });
  ASSERT_FALSE(hover.is_null()) << "no hover text for " << prefix;
  const uint8_t* texel = reinterpret_cast<const uint8_t*>(albedo.data()) + (size_t(py) * width + px) * 4;
  const std::string stored = prefix + "  stored albedo (rgba8_srgb) Albedo.R " + std::to_string(texel[0]) + " Albedo.G " +
                             std::to_string(texel[1]) + " Albedo.B " + std::to_string(texel[2]);
  EXPECT_EQ(hover["text"].get<std::string>().rfind(stored, 0), 0u) << hover["text"] << "\nexpected to start with " << stored;
  gui::Screenshot shot;
  std::string error;
  ASSERT_TRUE(gui::screenshot(xvfb_.display, (dir_ / "paused.png").string(), shot, error)) << error;

  // C: the frozen frame written as a capture, every target's texels the app's own.
  xdotool("key --window " + wid_ + " c");
  const json written = waitEvent([](const json& j) { return j["event"] == "capture"; });
  ASSERT_FALSE(written.is_null());
  const std::string text = written["status"];
  ASSERT_EQ(text.rfind("wrote ", 0), 0u) << text;
  Capture capture;
  ASSERT_TRUE(loadCapture((dir_ / text.substr(6)).string(), capture, error)) << error;
  size_t targets = 0;
  for (const json& t : cam["targets"]) {
    const std::string name = t["name"];
    SCOPED_TRACE("target " + name);
    const int i = capture.frame.indexOf(name);
    ASSERT_GE(i, 0);
    const CpuImage& img = capture.frame.images[size_t(i)].image;
    const std::string bytes = readFile(dump / t["file"].get<std::string>());
    ASSERT_EQ(img.data.size(), bytes.size());
    EXPECT_EQ(std::memcmp(img.data.data(), bytes.data(), bytes.size()), 0) << "the captured texels are not the app's";
    ++targets;
  }
  EXPECT_EQ(targets, 7u);

  // Closing the viewer detaches: the application runs on.
  xdotool("key --window " + wid_ + " ctrl+q");
  int viewerStatus = -1;
  ASSERT_TRUE(gui::waitExit(viewer_, 30.0, viewerStatus)) << "the viewer did not quit";
  viewer_ = -1;
  EXPECT_EQ(viewerStatus, 0) << "validation messages or a failure; see " << (dir_ / "viewer.log");
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  EXPECT_EQ(kill(app_, 0), 0) << "the application did not run on after the viewer closed";
  EXPECT_NE(readFile(dir_ / "viewer.log").find("runs on"), std::string::npos);
}

TEST_F(GuiAttachTest, WhenTheApplicationExitsItsLastFrameStaysWithItsExitCode) {
  startViewer("--frames 40 --size 160x90");
  size_t fromStart = 0;  // it may have ended before the window was ready
  const json exited = gui::waitForLine((dir_ / "events.jsonl").string(), 60.0,
                                       [](const json& j) { return j["event"] == "attach_state" && j["state"] == "exited"; }, fromStart);
  ASSERT_FALSE(exited.is_null());
  EXPECT_EQ(exited["code"], 0);
  EXPECT_NE(exited["status"].get<std::string>().find("application exited (code 0)"), std::string::npos) << exited["status"];
  // The window stays, still showing a frame of the application's.
  xdotool("key --window " + wid_ + " 1");
  const json grid = waitEvent([](const json& j) { return j["event"] == "layout" && j["views"].size() > 1; });
  ASSERT_FALSE(grid.is_null());
  for (const json& v : grid["views"]) EXPECT_FALSE(v.contains("unavailable")) << v.dump();
  xdotool("key --window " + wid_ + " ctrl+q");
  int status = -1;
  ASSERT_TRUE(gui::waitExit(viewer_, 30.0, status));
  viewer_ = -1;
  EXPECT_EQ(status, 0) << "see " << (dir_ / "viewer.log");
}

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
  int status = 0;
  gui::run(std::string("'") + FOREIGN_DEFERRED_BINARY + "' --frames " + std::to_string(frozen + 1) + " --dump '" +
               dump.string() + "' 2>&1",
           &status);
  ASSERT_EQ(status, 0);
  const json cam = json::parse(std::ifstream(dump / "camera.json"));
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
