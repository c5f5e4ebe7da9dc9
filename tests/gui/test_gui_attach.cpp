// The viewer on an attached application, as a person uses it: `gblens attach --layout L -- APP`
// under Xvfb, APP the independent test subject tests/subjects/foreign_deferred (another renderer:
// unnamed images, no labels, its layout's targets picked by render pass and attachment index). The
// grid shows exactly the layout's quantities; Space freezes the frame (no more frames taken, the
// application runs on); the hover text's stored codes and the capture written with C are the
// texels the application itself read back for that frame (its own --dump, run again without any
// layer: the app is deterministic). On the frozen frame a click probes a pixel and ctrl + left drag
// selects a region, as a person does: the dossier holds only the layout's quantities, and its stored
// bits and decoded values (AO, sRGB albedo, normal, view-space position, depth), the region's
// rectangle, pixel and surface counts and its statistics (AO, albedo; surfaces only) are those the
// test decodes itself from the app's dump. Closing the viewer leaves the application running. A
// short run ends while attached: its last frame stays with "application exited (code 0)".
#include "tests/support/test_paths.h"
#include <gtest/gtest.h>
#include <signal.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <thread>

#include "tests/gui/attach_session.h"
#include "tests/gui/foreign_dump.h"
#include "tests/gui/gui_util.h"
#include "views/capture/capture.h"

namespace gb {

namespace fs = std::filesystem;
using nlohmann::json;
using namespace attach_gui;

namespace {

// The pointer on texel (x, y) of a view of the layout event: the whole screen position at the
// texel's centre, and the texel the viewer takes that position for ((position - origin) / scale,
// floored, views/ui/view_layout.cpp texelAt). A grid tile shows 1.58 texels per screen pixel here, so
// that may be the texel before: the test expects the texel under the pointer, not the one it aimed at.
struct Pointer {
  int sx = 0, sy = 0;
  uint32_t x = 0, y = 0;
  std::string at() const { return std::to_string(sx) + " " + std::to_string(sy); }
};
Pointer pointerAt(const json& view, uint32_t x, uint32_t y) {
  const double ox = view["origin"][0], oy = view["origin"][1], scale = view["scale"];
  Pointer p;
  p.sx = int(std::floor(ox + (x + 0.5) * scale));
  p.sy = int(std::floor(oy + (y + 0.5) * scale));
  p.x = uint32_t(std::floor((p.sx - ox) / scale));
  p.y = uint32_t(std::floor((p.sy - oy) / scale));
  return p;
}

// The probe's dossier at (x, y) against the app's own texels there: the stored bits of three targets
// and the decoded values of five quantities, decoded by the test (foreign_dump.h).
void checkDossier(const json& d, const gui::ForeignDump& dump, uint32_t x, uint32_t y) {
  ASSERT_TRUE(dump.surface(x, y)) << "the probed pixel must hold a surface for the decoded values to mean anything";
  EXPECT_EQ(d["pixel"], json({x, y}));
  std::map<std::string, json> channels, quantities;
  for (const json& t : d["targets"])
    for (const json& c : t.value("channels", json::array()))
      channels[t["target"].get<std::string>() + "/" + c["name"].get<std::string>()] = c;
  for (const json& q : d["quantities"]) quantities[q["name"]] = q;
  auto bits = [&](const std::string& key) {  // "0x..." in the dossier
    return channels.count(key) ? std::stoul(channels[key]["bits"].get<std::string>(), nullptr, 16) : ~0ul;
  };
  auto values = [&](const std::string& name) { return quantities.count(name) ? quantities[name]["values"] : json::array(); };
  EXPECT_EQ(bits("occlusion/AO"), dump.code("occlusion", x, y));
  ASSERT_EQ(values("Albedo").size(), 3u) << d.dump();
  ASSERT_EQ(values("P").size(), 3u) << d.dump();
  ASSERT_GE(values("N").size(), 3u) << d.dump();
  for (uint32_t c = 0; c < 3; ++c) {
    SCOPED_TRACE("channel " + std::to_string(c));
    EXPECT_EQ(bits("albedo/Albedo." + std::string(1, "RGB"[c])), dump.code("albedo", x, y, c));
    EXPECT_EQ(bits("position/P." + std::string(1, "XYZ"[c])), dump.f32Bits("position", x, y, c));
    EXPECT_DOUBLE_EQ(values("Albedo")[c].get<double>(), dump.albedo(x, y, c));
    EXPECT_EQ(values("P")[c].get<double>(), double(dump.f32("position", x, y, c)));  // view space, as stored
    EXPECT_NEAR(values("N")[c].get<double>(), dump.normal(x, y)[c], 1e-12);
  }
  ASSERT_EQ(values("AO").size(), 1u) << d.dump();
  EXPECT_DOUBLE_EQ(values("AO")[0].get<double>(), dump.occlusion(x, y));
  ASSERT_EQ(values("Depth").size(), 1u) << d.dump();
  EXPECT_EQ(values("Depth")[0].get<double>(), double(dump.f32("depth", x, y)));  // hardware depth, as stored
}

// A region's statistics against the same figures computed by the test over the rectangle it
// reports: every pixel counts for a stored channel, only those with a surface (position.w is not
// the clear value) for a surface quantity's decoded values (views/analysis/region_stats.h).
void checkRegion(const json& stats, const gui::ForeignDump& dump) {
  const json& r = stats["rect"];
  const uint32_t x0 = r["x"], y0 = r["y"], w = r["width"], h = r["height"];
  ASSERT_LE(x0 + w, dump.width);
  ASSERT_LE(y0 + h, dump.height);
  std::vector<double> aoStored, ao, albedo[3];
  uint64_t surfaces = 0;
  for (uint32_t y = y0; y < y0 + h; ++y)
    for (uint32_t x = x0; x < x0 + w; ++x) {
      aoStored.push_back(dump.occlusion(x, y));
      if (!dump.surface(x, y)) continue;
      ++surfaces;
      ao.push_back(dump.occlusion(x, y));
      for (uint32_t c = 0; c < 3; ++c) albedo[c].push_back(dump.albedo(x, y, c));
    }
  EXPECT_EQ(stats["pixels"], uint64_t(w) * h);
  EXPECT_EQ(stats["surface_pixels"], surfaces);
  EXPECT_GT(surfaces, 0u);
  EXPECT_LT(surfaces, uint64_t(w) * h) << "the rectangle should hold background too, so the surface mask is tested";
  auto find = [&](const char* list, const std::string& target, const std::string& series) {
    for (const json& s : stats[list])
      if (s["target"] == target && s["series"] == series) return s;
    return json();
  };
  auto same = [](const json& got, const gui::Summary& want, const std::string& what) {
    SCOPED_TRACE(what);
    ASSERT_FALSE(got.is_null()) << "no series";
    EXPECT_EQ(got["count"], want.count);
    EXPECT_EQ(got["min"].get<double>(), want.min);
    EXPECT_EQ(got["max"].get<double>(), want.max);
    // Summed in another order; one code off at one pixel would move it by 2e-7.
    EXPECT_NEAR(got["mean"].get<double>(), want.mean, 1e-9);
  };
  same(find("channels", "occlusion", "AO"), gui::summarize(aoStored), "stored occlusion (every pixel)");
  same(find("quantities", "occlusion", "AO"), gui::summarize(ao), "AO (surfaces)");
  EXPECT_EQ(find("quantities", "occlusion", "AO").value("surfaces_only", false), true);
  for (uint32_t c = 0; c < 3; ++c) {
    const std::string series = "Albedo." + std::string(1, "RGB"[c]);
    same(find("quantities", "albedo", series), gui::summarize(albedo[c]), series + " (surfaces)");
  }
}

}  // namespace

TEST_F(GuiAttachTest, TheStreamShowsTheLayoutsViewsPausesAndCapturesTheAppsOwnTexels) {
  startViewer("--frames 16384");  // minutes: it runs on while the test pauses, captures and closes
  // Live: frames keep coming.
  ASSERT_FALSE(waitEvent([](const json& j) { return j["event"] == "attach_frame" && j["received"] >= 3; }).is_null());
  // Paced, the viewer's default (what pacing does: AttachPacing.*, VkCube.APaced...): the layer says so.
  const json paced = waitEvent([](const json& j) { return j["event"] == "attach_frame"; });
  ASSERT_FALSE(paced.is_null());
  EXPECT_TRUE(paced.value("paced", false)) << paced.dump();

  // The grid: exactly the layout's quantities, all of them with something to show.
  xdotool("key --window " + wid_ + " 1");
  const json grid = waitEvent([](const json& j) { return j["event"] == "layout" && j["views"].size() > 1; });
  ASSERT_FALSE(grid.is_null());
  std::vector<std::string> shown, declared;
  json albedoView, aoView;
  for (const json& v : grid["views"]) {
    shown.push_back(v["view"]);
    EXPECT_FALSE(v.contains("unavailable")) << v.dump();
    if (v["view"] == "Albedo") albedoView = v;
    if (v["view"] == "AO") aoView = v;
  }
  const json layout = json::parse(std::ifstream(FOREIGN_DEFERRED_DIR + "/layout.json"));
  for (const json& t : layout["targets"])
    for (const json& q : t["quantities"]) declared.push_back(q["name"]);
  std::sort(shown.begin(), shown.end());
  std::sort(declared.begin(), declared.end());
  EXPECT_EQ(shown, declared);
  ASSERT_FALSE(albedoView.is_null());
  ASSERT_FALSE(aoView.is_null());

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
  const json cam = dumpAppFrame(frozen);
  ASSERT_FALSE(cam.is_null());
  gui::ForeignDump texels;
  std::string error;
  ASSERT_TRUE(texels.load(dump, error)) << error;
  const uint32_t width = texels.width, height = texels.height;

  // Hover over a texel of the albedo view: the stored codes are those the app wrote.
  const Pointer hovered = pointerAt(albedoView, width / 2, height * 2 / 3);
  const uint32_t px = hovered.x, py = hovered.y;
  xdotool("mousemove --window " + wid_ + " " + hovered.at());
  const std::string prefix = "Albedo (" + std::to_string(px) + ", " + std::to_string(py) + ")";
  const json hover = waitEvent([&](const json& j) { return j["event"] == "hover" && j["text"].get<std::string>().rfind(prefix, 0) == 0; });
  ASSERT_FALSE(hover.is_null()) << "no hover text for " << prefix;
  const std::string stored = prefix + "  stored albedo (rgba8_srgb) Albedo.R " + std::to_string(texels.code("albedo", px, py, 0)) +
                             " Albedo.G " + std::to_string(texels.code("albedo", px, py, 1)) + " Albedo.B " +
                             std::to_string(texels.code("albedo", px, py, 2));
  EXPECT_EQ(hover["text"].get<std::string>().rfind(stored, 0), 0u) << hover["text"] << "\nexpected to start with " << stored;
  gui::Screenshot shot;
  ASSERT_TRUE(gui::screenshot(xvfb_.display, (dir_ / "paused.png").string(), shot, error)) << error;

  // A click on the AO view probes a texel of the frozen frame: the dossier (--probe-log) holds exactly
  // the layout's quantities, nothing of gblens's own renderer, and the app's texels at the pixel. The
  // texel: a surface the pointer can be put on, half occluded (neither code 0 nor 255: the decoding
  // shows); the frozen frame's camera differs from run to run.
  Pointer clicked = pointerAt(aoView, px, py);
  auto offHalf = [&](const Pointer& p) { return std::abs(int(texels.code("occlusion", p.x, p.y)) - 128); };
  for (uint32_t y = height / 3; y < height * 5 / 6; ++y)
    for (uint32_t x = width / 8; x < width * 7 / 8; ++x) {
      const Pointer p = pointerAt(aoView, x, y);
      if (p.x == x && p.y == y && texels.surface(x, y) && offHalf(p) < offHalf(clicked)) clicked = p;
    }
  xdotool("mousemove --window " + wid_ + " " + clicked.at() + " click 1");
  const json probe = waitEvent([](const json& j) { return j["event"] == "probe"; });
  ASSERT_FALSE(probe.is_null()) << "no probe after the click";
  EXPECT_EQ(probe["pixel"], json({clicked.x, clicked.y}));
  size_t probeCursor = 0;
  const json dossier = gui::waitForLine((dir_ / "probe.jsonl").string(), 10.0, [](const json&) { return true; }, probeCursor);
  ASSERT_FALSE(dossier.is_null()) << "no dossier in probe.jsonl";
  std::vector<std::string> probed;
  for (const json& q : dossier["quantities"]) probed.push_back(q["name"]);
  std::sort(probed.begin(), probed.end());
  EXPECT_EQ(probed, declared);
  // gblens's own frame's sections are there (the JSON has one shape, docs/schemas) and null.
  for (const char* gblensOnly : {"shadow_map", "hdr", "final"})
    EXPECT_TRUE(dossier.contains(gblensOnly) && dossier[gblensOnly].is_null()) << gblensOnly;
  checkDossier(dossier, texels, clicked.x, clicked.y);

  // Ctrl + left drag over a rectangle of the albedo view (the sky above the objects, their feet
  // below): the region event's statistics are the app's texels over the rectangle it reports. Pauses
  // between the steps: the viewer sees the press, the moves and the release in frames of their own.
  const Pointer from = pointerAt(albedoView, width / 16, height / 6);
  const Pointer to = pointerAt(albedoView, width * 5 / 8, height * 13 / 18);
  const Pointer middle = pointerAt(albedoView, (from.x + to.x) / 2, (from.y + to.y) / 2);
  const std::string move = " mousemove --window " + wid_ + " ";
  xdotool("keydown ctrl" + move + from.at() + " sleep 0.05 mousedown 1 sleep 0.05" + move + middle.at() + " sleep 0.05" + move +
          to.at() + " sleep 0.05 mouseup 1 sleep 0.05 keyup ctrl");
  const json region = waitEvent([](const json& j) { return j["event"] == "region"; });
  ASSERT_FALSE(region.is_null()) << "no region statistics after ctrl + drag";
  // Both corners' texels included.
  const json rect = {{"x", from.x}, {"y", from.y}, {"width", to.x - from.x + 1}, {"height", to.y - from.y + 1}};
  EXPECT_EQ(region["stats"]["rect"], rect);
  checkRegion(region["stats"], texels);
  std::this_thread::sleep_for(std::chrono::milliseconds(200));  // the Region panel drawn with the numbers
  ASSERT_TRUE(gui::screenshot(xvfb_.display, (dir_ / "region.png").string(), shot, error)) << error;

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

}  // namespace gb
