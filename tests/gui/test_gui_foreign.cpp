// The viewer on another renderer's G-buffer, as a person uses it: the RenderDoc capture of
// tests/subjects/foreign_deferred imported with its hand-written layout and opened under Xvfb. The
// grid shows exactly the layout's quantities (no shadow, specular or stencil stand-ins); hovering a
// pixel shows the stored texel as the application wrote it (its own --dump of the same frame); a
// click probes the pixel and the dossier holds only the layout's quantities.
#include "tests/support/test_paths.h"
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>
#include <chrono>

#include "tests/gui/gui_util.h"

namespace gb {

namespace fs = std::filesystem;

namespace {

const std::string kLayout = FOREIGN_DEFERRED_DIR + "/layout.json";
const std::string kOut = GBLENS_BUILD_DIR + "/foreign";

std::string readBytes(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(f), {});
}

}  // namespace

class ForeignGui : public ::testing::Test, protected gui::Session {
 protected:
  void SetUp() override {
    if (!gui::haveTool("Xvfb")) GTEST_SKIP() << "Xvfb is not installed (apt-get install xvfb)";
    ASSERT_EQ(gui::missingTool(), "") << "is missing (debian-packages.txt lists it; run make deps)";
    std::string error;
    ASSERT_TRUE(openDisplay(fs::path(GBLENS_BUILD_DIR) / "gui_foreign_test", 1280, 720, error)) << error;
  }
  void TearDown() override { closeDisplay(); }
};

TEST_F(ForeignGui, TheGridIsTheLayoutsQuantitiesAndHoverShowsTheStoredTexels) {
  const std::string capture = (dir_ / "imported").string();
  int status = -1;
  const std::string out = gui::run("'" + GBLENS_BINARY + "' import '" + kOut + "/foreign.rdc' --layout '" + kLayout + "' -o '" +
                                   capture + "' 2>&1", &status);
  ASSERT_EQ(status, 0) << out;
  // The app's own read-back of the captured frame (tests/subjects/foreign_deferred/README.md).
  const nlohmann::json camera = nlohmann::json::parse(std::ifstream(kOut + "/dump/camera.json"));
  const uint32_t w = camera["width"], h = camera["height"];
  const std::string occlusion = readBytes(kOut + "/dump/occlusion.bin");
  const std::string albedo = readBytes(kOut + "/dump/albedo.bin");
  ASSERT_EQ(occlusion.size(), size_t(w) * h);
  ASSERT_EQ(albedo.size(), size_t(w) * h * 4);

  viewer_ = gui::spawn({GBLENS_BINARY, "view", "--capture", capture, "--validate", "--window", "1280x720", "--event-log",
                        (dir_ / "events.jsonl").string(), "--probe-log", (dir_ / "probe.jsonl").string()},
                       {"DISPLAY=" + xvfb_.display}, (dir_ / "viewer.log").string());
  ASSERT_FALSE(waitEvent([](const nlohmann::json& j) { return j["event"] == "ready"; }, 60.0).is_null())
      << "the viewer did not present the capture; see " << (dir_ / "viewer.log");
  std::string wid = xdotool("search --onlyvisible --name '^gblens'");
  wid = wid.substr(0, wid.find('\n'));
  ASSERT_FALSE(wid.empty());

  // The grid: exactly the layout's quantities.
  xdotool("key --window " + wid + " 1");
  nlohmann::json grid = waitEvent([](const nlohmann::json& j) { return j["event"] == "layout" && j["views"].size() > 1; });
  ASSERT_FALSE(grid.is_null());
  gui::Screenshot shot;
  std::string error;
  ASSERT_TRUE(gui::screenshot(xvfb_.display, (dir_ / "grid.png").string(), shot, error)) << error;
  std::vector<std::string> shown, declared;
  std::map<std::string, nlohmann::json> views;
  for (const nlohmann::json& v : grid["views"]) {
    shown.push_back(v["view"]);
    views[v["view"]] = v;
    EXPECT_FALSE(v.contains("unavailable")) << v.dump();
  }
  const nlohmann::json layout = nlohmann::json::parse(std::ifstream(kLayout));
  for (const nlohmann::json& t : layout["targets"])
    for (const nlohmann::json& q : t["quantities"]) declared.push_back(q["name"]);
  std::sort(shown.begin(), shown.end());
  std::sort(declared.begin(), declared.end());
  EXPECT_EQ(shown, declared);

  // Hover over pixels of the occlusion and albedo views: the stored codes are the app's bytes.
  struct Probe {
    const char* view;
    const char* stored;  // the head of the stored part
    uint32_t x, y;
  };
  const Probe probes[] = {{"AO", "stored occlusion (r8_unorm)", w / 2, h / 2}, {"AO", "stored occlusion (r8_unorm)", w / 3, 2 * h / 3},
                          {"Albedo", "stored albedo (rgba8_srgb)", w / 2, h / 2}};
  for (const Probe& p : probes) {
    SCOPED_TRACE(std::string(p.view) + " " + std::to_string(p.x) + "," + std::to_string(p.y));
    ASSERT_TRUE(views.count(p.view));
    const nlohmann::json& v = views[p.view];
    const double sx = double(v["origin"][0]) + (p.x + 0.5) * double(v["scale"]);
    const double sy = double(v["origin"][1]) + (p.y + 0.5) * double(v["scale"]);
    xdotool("mousemove --window " + wid + " " + std::to_string(int(sx)) + " " + std::to_string(int(sy)));
    // The grid may show the image scaled: the pixel under the mouse is the one the text names.
    // "AO (159, 90)  stored occlusion (r8_unorm) AO 229  -> occlusion 0.898": the numbers after
    // each channel name, up to the decoded part.
    nlohmann::json hover = waitEvent([&](const nlohmann::json& j) {
      const std::string t = j.value("text", "");
      return j["event"] == "hover" && j["view"] == p.view && t.find(p.stored) != std::string::npos;
    });
    ASSERT_FALSE(hover.is_null()) << "no hover text over " << p.view;
    const std::string text = hover["text"];
    uint32_t hx = 0, hy = 0;
    ASSERT_EQ(std::sscanf(text.c_str() + text.find('('), "(%u, %u)", &hx, &hy), 2) << text;
    EXPECT_LE(std::abs(int(hx) - int(p.x)), 2) << text;
    EXPECT_LE(std::abs(int(hy) - int(p.y)), 2) << text;
    std::istringstream words(text.substr(text.find(p.stored) + std::strlen(p.stored), text.find(" -> ") - text.find(p.stored) - std::strlen(p.stored)));
    std::vector<long> codes;
    for (std::string name, value; words >> name >> value;) codes.push_back(std::stol(value));
    const size_t texel = size_t(hy) * w + hx;
    if (std::string(p.view) == "AO") {
      ASSERT_GE(codes.size(), 1u) << hover["text"];
      EXPECT_EQ(codes[0], long(uint8_t(occlusion[texel]))) << hover["text"];
    } else {
      ASSERT_GE(codes.size(), 3u) << hover["text"];
      for (int c = 0; c < 3; ++c) EXPECT_EQ(codes[size_t(c)], long(uint8_t(albedo[texel * 4 + size_t(c)]))) << hover["text"];
    }
  }

  // A click probes that pixel: the dossier holds the layout's quantities only.
  xdotool("click 1");
  ASSERT_FALSE(waitEvent([](const nlohmann::json& j) { return j["event"] == "probe_shown"; }).is_null());
  size_t cursor = 0;
  nlohmann::json d = gui::waitForLine((dir_ / "probe.jsonl").string(), 10.0, [](const nlohmann::json&) { return true; }, cursor);
  ASSERT_FALSE(d.is_null());
  std::vector<std::string> probed;
  for (const nlohmann::json& q : d["quantities"]) probed.push_back(q["name"]);
  std::sort(probed.begin(), probed.end());
  EXPECT_EQ(probed, declared);
  for (const char* gblensOnly : {"shadow_map", "hdr", "final"})  // one shape for every layout: null here
    EXPECT_TRUE(d.contains(gblensOnly) && d[gblensOnly].is_null()) << gblensOnly;
  std::this_thread::sleep_for(std::chrono::milliseconds(800));  // the panel's tables settle their widths
  ASSERT_TRUE(gui::screenshot(xvfb_.display, (dir_ / "probe.png").string(), shot, error)) << error;

  xdotool("key --window " + wid + " ctrl+q");
  ASSERT_TRUE(gui::waitExit(viewer_, 30.0, status)) << "the viewer did not quit";
  viewer_ = -1;
  EXPECT_EQ(status, 0) << "validation messages or a failure; see " << (dir_ / "viewer.log");
}

}  // namespace gb
