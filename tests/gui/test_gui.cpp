// The viewer as a person uses it: a real window under an Xvfb of the test's own, keys 1-9 / 0 /
// Return and a click from xdotool, screenshots checked by pixel statistics (the grid shows nine
// different views; each key shows its view), the clicked pixel's dossier (--probe-log) checked
// against a headless render of the same frame, and zero validation messages (--validate: the
// viewer exits non-zero on any). Screenshots stay in the build tree (gui_test/TEST/) to look at.
#include "tests/support/test_paths.h"
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <thread>

#include "renderer/scene/builtin.h"
#include "tests/gpu/gpu_test.h"
#include "tests/gui/gui_util.h"

namespace gb {

namespace fs = std::filesystem;

class GuiTest : public GpuTest {
 protected:
  void SetUp() override {
    if (!gui::haveTool("Xvfb")) GTEST_SKIP() << "Xvfb is not installed (apt-get install xvfb): no display to test the viewer on";
    ASSERT_EQ(gui::missingTool(), "") << "is missing (debian-packages.txt lists it; run make deps)";
    GpuTest::SetUp();
    // One folder per test: CTest runs them in parallel, and each starts by emptying its own.
    dir_ = fs::path(GBLENS_BUILD_DIR) / "gui_test" / ::testing::UnitTest::GetInstance()->current_test_info()->name();
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    std::string error;
    ASSERT_TRUE(xvfb_.start(kScreenW, kScreenH, error)) << error;
  }
  void TearDown() override {
    gui::terminate(viewer_);
    xvfb_.stop();
    if (!IsSkipped()) GpuTest::TearDown();
  }

  std::string xdotool(const std::string& args) {
    return gui::run("DISPLAY=" + xvfb_.display + " xdotool " + args + " 2>&1");
  }
  // Generous: lavapipe compiles each new view pipeline at first use (seconds on a loaded machine).
  nlohmann::json waitEvent(const std::function<bool(const nlohmann::json&)>& pred, double seconds = 90.0) {
    return gui::waitForLine(eventLog(), seconds, pred, eventCursor_);
  }
  std::string eventLog() const { return (dir_ / "events.jsonl").string(); }
  std::string probeLog() const { return (dir_ / "probe.jsonl").string(); }
  // Waits for the layout showing `view` alone (or the grid when view is empty).
  nlohmann::json waitLayout(const std::string& view) {
    return waitEvent([&](const nlohmann::json& j) {
      if (j["event"] != "layout") return false;
      if (view.empty()) return j["views"].size() > 2;
      return j["views"].size() == 1 && j["views"][0]["view"] == view;
    });
  }
  gui::Screenshot shoot(const std::string& name) {
    gui::Screenshot s;
    std::string error;
    EXPECT_TRUE(gui::screenshot(xvfb_.display, (dir_ / (name + ".png")).string(), s, error)) << error;
    return s;
  }
  // The image part of a view, in screen pixels (the window sits at the screen's origin).
  std::vector<float> viewThumb(const gui::Screenshot& s, const nlohmann::json& v) {
    double ox = v["origin"][0], oy = v["origin"][1], sc = v["scale"];
    double iw = double(v["image"][0]) * sc, ih = double(v["image"][1]) * sc;
    double rx = v["rect"][0], ry = v["rect"][1], rw = v["rect"][2], rh = v["rect"][3];
    int x0 = int(std::max(ox, rx)) + 2, y0 = int(std::max(oy, ry + 34)) + 2;  // below the label
    int x1 = int(std::min(ox + iw, rx + rw)) - 2, y1 = int(std::min(oy + ih, ry + rh)) - 2;
    return gui::thumbnail(s, x0 + windowX_, y0 + windowY_, x1 + windowX_, y1 + windowY_, 8);
  }

  static constexpr int kScreenW = 1280, kScreenH = 720;
  static constexpr uint32_t kW = 192, kH = 108;
  static constexpr double kTime = 1.5;
  fs::path dir_;
  gui::Xvfb xvfb_;
  pid_t viewer_ = -1;
  int windowX_ = 0, windowY_ = 0;
  size_t eventCursor_ = 0;  // events before this line were consumed
  nlohmann::json previousLayout_;
};

TEST_F(GuiTest, KeysShowEveryViewAndAClickProbesThePixelAsAHeadlessRenderDoes) {
  const std::string size = std::to_string(kW) + "x" + std::to_string(kH);
  // Full frames only: auto's reduction depends on measured times (the next test checks it).
  viewer_ = gui::spawn({GBLENS_BINARY, "view", "builtin:temple", "--validate", "--size", size, "--time", "1.5", "--paused",
                        "--window", "1280x720", "--reduce-while-moving", "off", "--event-log", eventLog(), "--probe-log",
                        probeLog(), "--probe-reference"},
                       {"DISPLAY=" + xvfb_.display}, (dir_ / "viewer.log").string());
  ASSERT_FALSE(waitEvent([](const nlohmann::json& j) { return j["event"] == "ready"; }, 60.0).is_null())
      << "the viewer did not present a frame; see " << (dir_ / "viewer.log");
  std::string wid = xdotool("search --onlyvisible --name '^gblens'");
  wid = wid.substr(0, wid.find('\n'));
  ASSERT_FALSE(wid.empty());
  std::string geometry = xdotool("getwindowgeometry " + wid);
  std::sscanf(geometry.c_str() + geometry.find("Position:"), "Position: %d,%d", &windowX_, &windowY_);
  xdotool("mousemove --window " + wid + " 640 715");  // keep the pointer off the views (status bar)

  // 1: the grid: every view of gblens's layout the frame holds, each non-uniform, no two alike.
  xdotool("key --window " + wid + " 1");
  nlohmann::json grid = waitLayout("");
  ASSERT_FALSE(grid.is_null()) << "key 1 did not show the grid";
  gui::Screenshot gridShot = shoot("grid");
  std::vector<std::vector<float>> tiles;
  for (const auto& v : grid["views"]) {
    tiles.push_back(viewThumb(gridShot, v));
    EXPECT_GT(gui::standardDeviation(tiles.back()), 0.01) << v["view"] << " looks blank";
  }
  for (size_t a = 0; a < tiles.size(); ++a)
    for (size_t b = a + 1; b < tiles.size(); ++b)
      EXPECT_GT(gui::meanAbsDifference(tiles[a], tiles[b]), 0.015)
          << grid["views"][a]["view"] << " and " << grid["views"][b]["view"] << " look the same";

  // 2..9, then 0 and Return: each key shows its view alone, and each looks different from the last.
  // The keys follow gblens's layout (assets/layouts/gblens.json): the display colour first, then its
  // quantities in order.
  const std::vector<std::pair<std::string, std::string>> keys = {
      {"2", "Albedo"}, {"3", "Specular"}, {"4", "Normal"}, {"5", "Shadow"}, {"6", "Depth"}, {"7", "HardwareDepth"},
      {"8", "Stencil"}, {"9", "ShadowMap"}, {"0", "Final"}, {"5", "Shadow"}, {"Return", "Final"}};
  std::vector<float> previous;
  for (const auto& [key, view] : keys) {
    xdotool("key --window " + wid + " " + key);
    nlohmann::json layout = waitLayout(view);
    ASSERT_FALSE(layout.is_null()) << "key " << key << " did not show " << view;
    previousLayout_ = layout["views"][0];
    std::vector<float> thumb = viewThumb(shoot("key_" + key + "_" + view), layout["views"][0]);
    EXPECT_GT(gui::standardDeviation(thumb), 0.01) << view << " looks blank";
    if (!previous.empty()) {
      EXPECT_GT(gui::meanAbsDifference(thumb, previous), 0.015) << view << " looks like the view before";
    }
    previous = thumb;
  }

  // A click on a known pixel of the final view: the dossier of exactly that pixel.
  nlohmann::json final = previousLayout_;
  const int px = 104, py = 80;  // the floor in front of the temple, under several lights
  double sx = double(final["origin"][0]) + (px + 0.5) * double(final["scale"]);
  double sy = double(final["origin"][1]) + (py + 0.5) * double(final["scale"]);
  xdotool("mousemove --window " + wid + " " + std::to_string(int(sx)) + " " + std::to_string(int(sy)) + " click 1");
  nlohmann::json probe = waitEvent([](const nlohmann::json& j) { return j["event"] == "probe"; });
  ASSERT_FALSE(probe.is_null()) << "the click produced no dossier";
  EXPECT_EQ(probe["pixel"], nlohmann::json({px, py}));
  nlohmann::json shown = waitEvent([](const nlohmann::json& j) { return j["event"] == "probe_shown"; });
  ASSERT_FALSE(shown.is_null()) << "the dossier was never presented";
  shoot("probe");
  size_t probeCursor = 0;
  nlohmann::json dossier = gui::waitForLine(probeLog(), 5.0, [](const nlohmann::json&) { return true; }, probeCursor);
  ASSERT_FALSE(dossier.is_null());
  EXPECT_EQ(dossier["pixel"], nlohmann::json({px, py}));
  EXPECT_TRUE(dossier["decoded"]["geometry"].get<bool>());

  // Quit (ctrl+Q): the exit status says whether any validation message appeared.
  xdotool("key --window " + wid + " ctrl+q");
  int status = -1;
  ASSERT_TRUE(gui::waitExit(viewer_, 30.0, status)) << "the viewer did not quit";
  viewer_ = -1;
  EXPECT_EQ(status, 0) << "validation messages or a failure; see " << (dir_ / "viewer.log");

  // Headless, in this process: the same frame's stored values at that pixel, bit for bit.
  Scene scene = builtinTemple(256);
  RenderOptions o;
  o.width = kW;
  o.height = kH;
  o.time = kTime;
  o.coverage = true;
  std::vector<Target> screen = {Target::AlbedoSpecular, Target::NormalShadow, Target::Depth, Target::DepthStencil,
                                Target::Hdr, Target::Final, Target::CoverageMasked, Target::CoverageFull};
  render(scene, o, {screen});
  int checked = 0;
  for (const auto& t : dossier["targets"]) {
    Target target;
    ASSERT_TRUE(parseTarget(t["target"], target));
    if (std::find(screen.begin(), screen.end(), target) == screen.end()) {
      if (target != Target::ShadowMap) {
        EXPECT_TRUE(t.contains("absent")) << t["target"];  // primitive_id, position: off
      }
      continue;
    }
    ASSERT_TRUE(t.contains("channels")) << t["target"] << ": " << t.value("absent", "");
    const CpuImage& img = renderer(scene).readback[size_t(target)];
    for (size_t c = 0; c < t["channels"].size(); ++c) {
      const auto& ch = t["channels"][c];
      EXPECT_EQ(ch["name"], img.channels[c]);
      EXPECT_EQ(std::stoul(ch["bits"].get<std::string>(), nullptr, 16), img.raw(px, py, uint32_t(c)))
          << t["target"] << " " << ch["name"];
      EXPECT_EQ(ch["value"].get<double>(), img.value(px, py, uint32_t(c))) << t["target"] << " " << ch["name"];
      ++checked;
    }
  }
  EXPECT_EQ(checked, 4 + 4 + 1 + 2 + 4 + 4 + 1 + 1);

  // Headless through the command line: a capture of the same frame probed by `gblens probe`
  // gives the same dossier (positions, shadow-map texels, lights, colours), number for number.
  std::string capture = (dir_ / "capture").string();
  int st = -1;
  gui::run(std::string(GBLENS_BINARY) + " capture builtin:temple --size " + size +
               " --time 1.5 --coverage on -o " + capture + " 2>&1", &st);
  ASSERT_EQ(st, 0);
  std::string text = gui::run(std::string(GBLENS_BINARY) + " probe " + capture + " " + std::to_string(px) + " " +
                                  std::to_string(py) + " --json --reference",
                              &st);
  ASSERT_EQ(st, 0);
  nlohmann::json headless = nlohmann::json::parse(text);
  // The Pixel panel's reference (--probe-reference) is the one `gblens probe --reference` computes.
  ASSERT_TRUE(dossier.contains("reference"));
  EXPECT_TRUE(dossier["reference"]["compared"].get<bool>()) << dossier["reference"].dump();
  for (const char* key : {"targets", "decoded", "position", "shadow_map", "lighting", "hdr", "final", "reference"})
    EXPECT_EQ(dossier[key], headless[key]) << key << "\nviewer:   " << dossier[key].dump() << "\nheadless: " << headless[key].dump();
}

// While the camera is dragged the viewer shows reduced frames (--reduce-while-moving 3: a third of
// the size each way, 64x36 for 192x108, rounded up), and when the drag stops the full frame
// replaces them; a click then probes the full-resolution frame.
TEST_F(GuiTest, AReducedFrameWhileMovingIsFollowedByAFullOne) {
  const std::string size = std::to_string(kW) + "x" + std::to_string(kH);
  viewer_ = gui::spawn({GBLENS_BINARY, "view", "builtin:temple", "--validate", "--size", size, "--time", "1.5", "--paused",
                        "--window", "1280x720", "--reduce-while-moving", "3", "--event-log", eventLog()},
                       {"DISPLAY=" + xvfb_.display}, (dir_ / "viewer.log").string());
  auto frame = [](int reducedBy, int w, int h) {
    return [=](const nlohmann::json& j) {
      return j["event"] == "frame" && j["reduced_by"] == reducedBy && j["size"] == nlohmann::json({w, h});
    };
  };
  ASSERT_FALSE(waitEvent(frame(1, int(kW), int(kH)), 60.0).is_null()) << "no first full frame; see " << (dir_ / "viewer.log");
  nlohmann::json layout = waitLayout("Final");
  ASSERT_FALSE(layout.is_null());
  std::string wid = xdotool("search --onlyvisible --name '^gblens'");
  wid = wid.substr(0, wid.find('\n'));
  ASSERT_FALSE(wid.empty());
  const nlohmann::json& view = layout["views"][0];
  const int cx = int(double(view["rect"][0]) + double(view["rect"][2]) * 0.5);
  const int cy = int(double(view["rect"][1]) + double(view["rect"][3]) * 0.5);

  // Right-drag (orbit) in steps, the button held between them.
  xdotool("mousemove --window " + wid + " " + std::to_string(cx) + " " + std::to_string(cy) + " mousedown 3");
  for (int i = 0; i < 4; ++i) xdotool("mousemove_relative -- 12 0 sleep 0.15");
  nlohmann::json reduced = waitEvent(frame(3, 64, 36));
  EXPECT_FALSE(reduced.is_null()) << "dragging showed no reduced frame";
  if (!reduced.is_null()) {
    EXPECT_EQ(reduced["full"], nlohmann::json({int(kW), int(kH)}));
  }
  xdotool("mouseup 3");
  nlohmann::json full = waitEvent(frame(1, int(kW), int(kH)));
  EXPECT_FALSE(full.is_null()) << "the reduced frame was not refined to the full size";
  shoot("refined");

  // The probe's pixel is a full-resolution one (texel coordinates of the full frame).
  const int px = 150, py = 90;
  double sx = double(view["origin"][0]) + (px + 0.5) * double(view["scale"]);
  double sy = double(view["origin"][1]) + (py + 0.5) * double(view["scale"]);
  xdotool("mousemove --window " + wid + " " + std::to_string(int(sx)) + " " + std::to_string(int(sy)) + " click 1");
  nlohmann::json probe = waitEvent([](const nlohmann::json& j) { return j["event"] == "probe"; });
  ASSERT_FALSE(probe.is_null()) << "the click produced no dossier";
  EXPECT_EQ(probe["pixel"], nlohmann::json({px, py}));

  xdotool("key --window " + wid + " ctrl+q");
  int status = -1;
  ASSERT_TRUE(gui::waitExit(viewer_, 30.0, status)) << "the viewer did not quit";
  viewer_ = -1;
  EXPECT_EQ(status, 0) << "validation messages or a failure; see " << (dir_ / "viewer.log");
}

// The reference error, live (issue 17, part 3): the viewer's "Reference error" window computes the
// maps for the frame on screen in a worker thread; written out (--reference-error DIR), every map
// is pixel for pixel the PNG `gblens error -o` writes for the same scene, size and time, and every
// decomposition term the EXR `gblens decompose` writes for a capture of that frame.
TEST_F(GuiTest, TheLiveReferenceErrorMapsAreThoseOfGblensError) {
  const std::string size = "160x90", out = (dir_ / "reference_error").string();
  viewer_ = gui::spawn({GBLENS_BINARY, "view", "builtin:temple", "--validate", "--size", size, "--time", "1.5", "--paused",
                        "--window", "1200x700", "--reduce-while-moving", "off", "--event-log", eventLog(),
                        "--reference-error", out},
                       {"DISPLAY=" + xvfb_.display}, (dir_ / "viewer.log").string());
  nlohmann::json done = waitEvent([](const nlohmann::json& j) { return j["event"] == "reference_error_written"; }, 120.0);
  ASSERT_FALSE(done.is_null()) << "no reference error; see " << (dir_ / "viewer.log");
  EXPECT_EQ(done["error"], "");
  std::this_thread::sleep_for(std::chrono::milliseconds(500));  // the window shows the map
  shoot("reference_error");
  std::string wid = xdotool("search --onlyvisible --name '^gblens'");
  xdotool("key --window " + wid.substr(0, wid.find('\n')) + " ctrl+q");
  int status = -1;
  ASSERT_TRUE(gui::waitExit(viewer_, 30.0, status)) << "the viewer did not quit";
  viewer_ = -1;
  EXPECT_EQ(status, 0) << "validation messages or a failure; see " << (dir_ / "viewer.log");
  const std::string cli = (dir_ / "gblens_error").string();
  int st = -1;
  gui::run(std::string(GBLENS_BINARY) + " error builtin:temple --size " + size + " --time 1.5 -o " + cli + " 2>&1", &st);
  ASSERT_EQ(st, 0);
  int maps = 0;
  for (const char* name : {"shadow", "silhouettes", "normal", "hdr", "position", "lighting"}) {
    auto pixels = [&](const std::string& dir) {
      return gui::run("convert " + dir + "/" + name + ".png rgba:- | sha256sum");
    };
    ASSERT_TRUE(fs::exists(out + "/" + name + ".png")) << name;
    ASSERT_TRUE(fs::exists(cli + "/" + name + ".png")) << name;
    const std::string viewer = pixels(out), reference = pixels(cli);
    const std::string empty = "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855";  // of no bytes
    EXPECT_NE(viewer.substr(0, 64), empty) << name << ".png: convert read nothing";
    EXPECT_EQ(viewer.substr(0, 64), reference.substr(0, 64)) << name << ".png differs";
    ++maps;
  }
  EXPECT_EQ(maps, 6);
  // The decomposition terms the window offers are `gblens decompose`'s of a capture of that frame.
  const std::string capture = (dir_ / "capture").string(), decomposed = (dir_ / "decomposed").string();
  gui::run(std::string(GBLENS_BINARY) + " capture builtin:temple --size " + size + " --time 1.5 -o " + capture + " 2>&1", &st);
  ASSERT_EQ(st, 0);
  gui::run(std::string(GBLENS_BINARY) + " decompose " + capture + " -o " + decomposed + " 2>&1", &st);
  ASSERT_EQ(st, 0);
  // Both written by writeExr from images of the same description: equal files, equal data.
  auto bytes = [](const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
  };
  for (const char* term : {"lighting", "diffuse", "specular", "sun", "point_lights", "light_count"}) {
    const std::string viewer = bytes(out + "/decompose/" + term + ".exr"), cli = bytes(decomposed + "/" + term + ".exr");
    ASSERT_GT(viewer.size(), 1000u) << term << ": missing or empty";  // compressed EXR
    EXPECT_TRUE(viewer == cli) << term << ": the viewer's decomposition differs from gblens decompose's";
  }
}

// The probe is anchored in the image (issue 26): click a pixel, orbit the camera (reduced frames while
// moving), and when the full frame returns the dossier is of the same pixel, saying its content changed;
// region statistics of a ctrl + drag finish while the animation is paused.
TEST_F(GuiTest, TheProbeKeepsItsPixelAcrossAnOrbitAndRegionsFinishWhilePaused) {
  const std::string size = std::to_string(kW) + "x" + std::to_string(kH);
  viewer_ = gui::spawn({GBLENS_BINARY, "view", "builtin:temple", "--validate", "--size", size, "--time", "1.5", "--paused",
                        "--window", "1280x720", "--reduce-while-moving", "3", "--event-log", eventLog()},
                       {"DISPLAY=" + xvfb_.display}, (dir_ / "viewer.log").string());
  nlohmann::json layout = waitLayout("Final");
  ASSERT_FALSE(layout.is_null()) << "no first frame; see " << (dir_ / "viewer.log");
  std::string wid = xdotool("search --onlyvisible --name '^gblens'");
  wid = wid.substr(0, wid.find('\n'));
  const nlohmann::json& view = layout["views"][0];
  auto at = [&](int px, int py) {
    return std::to_string(int(double(view["origin"][0]) + (px + 0.5) * double(view["scale"]))) + " " +
           std::to_string(int(double(view["origin"][1]) + (py + 0.5) * double(view["scale"])));
  };
  const int px = 104, py = 80;
  xdotool("mousemove --window " + wid + " " + at(px, py) + " click 1");
  nlohmann::json probe = waitEvent([](const nlohmann::json& j) { return j["event"] == "probe"; });
  ASSERT_FALSE(probe.is_null());
  EXPECT_EQ(probe["pixel"], nlohmann::json({px, py}));
  // Orbit a little (right drag): reduced frames, then the full one.
  xdotool("mousemove --window " + wid + " " + at(96, 54) + " mousedown 3");
  for (int i = 0; i < 3; ++i) xdotool("mousemove_relative -- 10 0 sleep 0.15");
  xdotool("mouseup 3");
  nlohmann::json refreshed = waitEvent([](const nlohmann::json& j) { return j["event"] == "probe_refreshed"; }, 60.0);
  ASSERT_FALSE(refreshed.is_null()) << "the probe did not follow the full frame; see " << (dir_ / "viewer.log");
  EXPECT_EQ(refreshed["pixel"], nlohmann::json({px, py})) << "the probe moved to another pixel";
  EXPECT_TRUE(refreshed["changed"].get<bool>()) << "the camera moved: the pixel's content changed";
  shoot("probe_after_orbit");
  // Paused: a region's statistics arrive (from the full frame on screen).
  xdotool("mousemove --window " + wid + " " + at(20, 30) + " sleep 0.2 keydown ctrl sleep 0.2 mousedown 1 sleep 0.2 " +
          "mousemove --window " + wid + " " + at(60, 70) + " sleep 0.3 mouseup 1 sleep 0.2 keyup ctrl");
  nlohmann::json region = waitEvent([](const nlohmann::json& j) { return j["event"] == "region"; }, 30.0);
  ASSERT_FALSE(region.is_null()) << "region statistics never finished while paused";
  EXPECT_EQ(region["stats"]["rect"], nlohmann::json({{"x", 20}, {"y", 30}, {"width", 41}, {"height", 41}}));
  xdotool("key --window " + wid + " ctrl+q");
  int status = -1;
  ASSERT_TRUE(gui::waitExit(viewer_, 30.0, status)) << "the viewer did not quit";
  viewer_ = -1;
  EXPECT_EQ(status, 0) << "validation messages or a failure; see " << (dir_ / "viewer.log");
}

}  // namespace gb
