// The compare viewer and the live reference error, as a person uses them (issue 26), under an Xvfb of
// the test's own with xdotool: Space flips A and B in place (the pane's pixels are A's final.png, then
// B's, then A's again, each the capture's own file within a code), FLIP of the colour views is what
// `gblens compare` reports; the reference error's maps join the grid as views, a click on one probes
// that pixel and its hover value is the probe's own count, and Escape cancels the computation with
// nothing written. Screenshots stay in the build tree (gui_test/TEST/) to look at.
#include "tests/support/test_paths.h"
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <thread>

#include "tests/gui/gpu_session.h"
#include "tests/gui/gui_util.h"

namespace gb {

namespace fs = std::filesystem;
using nlohmann::json;

class GuiCompareTest : public GpuGuiTest {
 protected:
  std::string folderPrefix() const override { return "gui_test/"; }

  // `gblens capture builtin:temple` at 192x108, time 1.5, with extra options.
  std::string capture(const std::string& name, const std::string& options) {
    const std::string out = (dir_ / name).string();
    int status = -1;
    gui::run(std::string(GBLENS_BINARY) + " capture builtin:temple --size 192x108 --time 1.5 " + options + " -o " + out + " 2>&1",
             &status);
    EXPECT_EQ(status, 0) << name;
    return out;
  }

};

namespace {

// The screen point of texel (x, y)'s centre in a view of a layout event.
std::pair<int, int> screenOf(const json& view, int x, int y) {
  return {int(double(view["origin"][0]) + (x + 0.5) * double(view["scale"])),
          int(double(view["origin"][1]) + (y + 0.5) * double(view["scale"]))};
}

// An 8-bit RGB image read with OpenImageIO (a capture's final.png).
struct Rgb8 {
  int width = 0, height = 0;
  std::vector<uint8_t> rgb;
};
Rgb8 readPng(const std::string& path) {
  Rgb8 out;
  auto in = OIIO::ImageInput::open(path);
  if (!in) return out;
  const OIIO::ImageSpec& spec = in->spec();
  std::vector<uint8_t> all(size_t(spec.width) * spec.height * spec.nchannels);
  in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT8, all.data());
  out.width = spec.width, out.height = spec.height;
  for (size_t i = 0; i < size_t(spec.width) * spec.height; ++i)
    for (int c = 0; c < 3; ++c) out.rgb.push_back(all[i * spec.nchannels + size_t(c)]);
  return out;
}

// FNV-1a of the pane's pixels (8-bit), to tell A, B and A again apart exactly.
uint64_t paneHash(const gui::Screenshot& s, const json& view) {
  const int x0 = int(double(view["rect"][0])), y0 = int(double(view["rect"][1]));
  const int x1 = x0 + int(double(view["rect"][2])), y1 = y0 + int(double(view["rect"][3]));
  uint64_t h = 1469598103934665603ull;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x)
      for (int c = 0; c < 3; ++c) h = (h ^ uint64_t(std::lround(s.at(x, y)[c] * 255.0f))) * 1099511628211ull;
  return h;
}

// The largest difference, in 8-bit codes, between the pane's texel centres and the image's texels.
int largestCodeDifference(const gui::Screenshot& s, const json& view, const Rgb8& image) {
  int worst = 0;
  for (int y = 0; y < image.height; y += 3)
    for (int x = 0; x < image.width; x += 3) {
      const auto [sx, sy] = screenOf(view, x, y);
      for (int c = 0; c < 3; ++c)
        worst = std::max(worst, std::abs(int(std::lround(s.at(sx, sy)[c] * 255.0f)) -
                                         int(image.rgb[(size_t(y) * image.width + x) * 3 + size_t(c)])));
    }
  return worst;
}

}  // namespace

// The swipe (key S) follows the mouse, as the review page's does: texels left of the mouse are A's
// final.png, those right of it B's, wherever the mouse goes; each side carries its letter
// (swipe_30.png, swipe_70.png).
TEST_F(GuiCompareTest, TheSwipeFollowsTheMouseAndEachSideIsItsCapture) {
  const std::string a = capture("A", ""), b = capture("B", "--lights 100");
  startViewer({"--capture", a, "--compare", b});
  xdotool("key --window " + wid_ + " s");
  json layout = waitEvent([](const json& j) { return j["event"] == "layout" && j["views"][0]["side"] == "split"; });
  ASSERT_FALSE(layout.is_null()) << "S did not show the swipe";
  const Rgb8 finalA = readPng(a + "/final.png"), finalB = readPng(b + "/final.png");
  for (double at : {0.3, 0.7}) {
    const json& r = layout["views"][0]["rect"];
    const int mx = int(double(r[0]) + double(r[2]) * at), my = int(double(r[1]) + double(r[3]) * 0.6);
    xdotool("mousemove --window " + wid_ + " " + std::to_string(mx) + " " + std::to_string(my));
    layout = waitEvent([&](const json& j) {
      return j["event"] == "layout" && j["views"][0].contains("split_at") &&
             std::abs(j["views"][0]["split_at"].get<double>() - at) < 2.0 / double(r[2]);
    });
    ASSERT_FALSE(layout.is_null()) << "the swipe did not follow the mouse to " << at;
    const json& view = layout["views"][0];
    const double split = double(view["rect"][0]) + double(view["rect"][2]) * view["split_at"].get<double>();
    int worstA = 0, worstB = 0, checkedA = 0, checkedB = 0;
    // The layout event follows the present, but Xvfb may show the frame a little later (a loaded
    // machine): the screen is read again, up to five times, until it shows the swipe there.
    for (int attempt = 0; attempt < 5 && (attempt == 0 || worstA > 1 || worstB > 1); ++attempt) {
      if (attempt) std::this_thread::sleep_for(std::chrono::milliseconds(300));
      gui::Screenshot shot;
      std::string error;
      ASSERT_TRUE(gui::screenshot(xvfb_.display, (dir_ / ("swipe_" + std::to_string(int(at * 100)) + ".png")).string(), shot, error))
          << error;
      worstA = worstB = checkedA = checkedB = 0;
      for (int y = finalA.height / 3; y < finalA.height; y += 2)  // below the labels
        for (int x = 0; x < finalA.width; x += 2) {
          const auto [sx, sy] = screenOf(view, x, y);
          if (std::abs(sx - split) < 8 || std::abs(sx - mx) < 12 && std::abs(sy - my) < 12) continue;  // the line, the mark
          const Rgb8& side = sx < split ? finalA : finalB;
          int d = 0;
          for (int c = 0; c < 3; ++c)
            d = std::max(d, std::abs(int(std::lround(shot.at(sx, sy)[c] * 255.0f)) - int(side.rgb[(size_t(y) * side.width + x) * 3 + size_t(c)])));
          (sx < split ? worstA : worstB) = std::max(sx < split ? worstA : worstB, d);
          ++(sx < split ? checkedA : checkedB);
        }
    }
    EXPECT_GT(checkedA, 100);
    EXPECT_GT(checkedB, 100);
    EXPECT_LE(worstA, 1) << "left of the swipe at " << at << " is not A";
    EXPECT_LE(worstB, 1) << "right of the swipe at " << at << " is not B";
  }
  quit();
}

// Space flips the pane between A and B (tev's workflow): the same view, zoom and pan, the label saying
// which; each side's pixels are its capture's final.png. FLIP of the colour views, computed by the
// viewer from its decoded views, is the FLIP `gblens compare` reports for final (LDR) and hdr (HDR).
TEST_F(GuiCompareTest, SpaceFlipsAAndBInPlaceAndTheirFlipIsGblensCompares) {
  const std::string a = capture("A", ""), b = capture("B", "--lights 100");
  startViewer({"--capture", a, "--compare", b});
  json layout = firstLayout_;
  ASSERT_FALSE(layout.is_null());
  ASSERT_EQ(layout["views"].size(), 1u);
  ASSERT_EQ(layout["views"][0]["view"], "Final");
  ASSERT_EQ(layout["views"][0]["side"], "a");
  const Rgb8 finalA = readPng(a + "/final.png"), finalB = readPng(b + "/final.png");
  ASSERT_EQ(finalA.width, 192);
  ASSERT_EQ(finalB.width, 192);

  std::vector<uint64_t> hashes;
  for (const char* side : {"a", "b", "a"}) {
    if (!hashes.empty()) {
      xdotool("key --window " + wid_ + " space");
      layout = waitEvent([&](const json& j) { return j["event"] == "layout" && j["views"][0]["side"] == side; });
      ASSERT_FALSE(layout.is_null()) << "Space did not show " << side;
    }
    const json& view = layout["views"][0];
    gui::Screenshot shot;
    std::string error;
    // The layout is logged after the frame showing it is presented.
    ASSERT_TRUE(gui::screenshot(xvfb_.display, (dir_ / ("pane_" + std::to_string(hashes.size()) + "_" + side + ".png")).string(),
                                shot, error))
        << error;
    hashes.push_back(paneHash(shot, view));
    EXPECT_LE(largestCodeDifference(shot, view, side == std::string("a") ? finalA : finalB), 1)
        << "the pane does not show " << side << "'s final.png";
  }
  EXPECT_NE(hashes[0], hashes[1]) << "A and B look the same";
  EXPECT_EQ(hashes[0], hashes[2]) << "A after two flips is not A";

  // FLIP (computed at open, in a worker) against gblens compare's.
  const json flip = findEvent([](const json& j) { return j["event"] == "flip"; }, 60.0);
  ASSERT_FALSE(flip.is_null()) << "no FLIP; see " << (dir_ / "viewer.log");

  // Hover: A's and B's values and |A - B| of the decoded (linear) colour, against both final.png's
  // codes read with OpenImageIO and decoded from sRGB here. A texel where the lights differ most.
  int tx = 0, ty = 0, most = -1;
  for (int y = 0; y < finalA.height; ++y)
    for (int x = 0; x < finalA.width; ++x) {
      const size_t i = (size_t(y) * finalA.width + x) * 3;
      const int d = std::abs(int(finalA.rgb[i]) - int(finalB.rgb[i]));
      if (d > most) most = d, tx = x, ty = y;
    }
  const auto [hx, hy] = screenOf(layout["views"][0], tx, ty);
  xdotool("mousemove --window " + wid_ + " " + std::to_string(hx) + " " + std::to_string(hy));
  const json hover = waitEvent([](const json& j) {
    return j["event"] == "hover" && j["text"].get<std::string>().find("|A-B|") != std::string::npos;
  });
  ASSERT_FALSE(hover.is_null()) << "no |A-B| in the hover text";
  const std::string hoverText = hover["text"];
  double diff[3] = {};
  ASSERT_EQ(std::sscanf(hoverText.c_str() + hoverText.find("|A-B|"), "|A-B| R %lf G %lf B %lf", &diff[0], &diff[1], &diff[2]), 3) << hoverText;
  auto linear = [](uint8_t code) {
    const double v = code / 255.0;
    return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
  };
  for (int c = 0; c < 3; ++c) {
    const size_t i = (size_t(ty) * finalA.width + tx) * 3 + size_t(c);
    EXPECT_NEAR(diff[c], std::abs(linear(finalA.rgb[i]) - linear(finalB.rgb[i])), 1e-6) << hoverText;
  }
  quit();
  int status = -1;
  const std::string text = gui::run(std::string(GBLENS_BINARY) + " compare " + a + " " + b + " --json - 2>/dev/null", &status);
  const json report = json::parse(text, nullptr, false);
  ASSERT_FALSE(report.is_discarded()) << text;
  int compared = 0;
  for (const json& f : report["flip"]) {
    const std::string view = f["target"] == "final" ? "Final" : "HDR";
    ASSERT_TRUE(flip["mean"].contains(view)) << flip.dump();
    EXPECT_NEAR(flip["mean"][view].get<double>(), f["mean"].get<double>(), 1e-6) << view;
    EXPECT_GT(f["mean"].get<double>(), 0.0);
    ++compared;
  }
  EXPECT_EQ(compared, 2);
}

// The reference error's maps are views of the live frame: they join the grid once computed (its
// progress counted every row it promised), a click on one probes that pixel, and the hovered light
// count is the number of point lights the probe's own dossier finds within their radius there.
TEST_F(GuiCompareTest, TheReferenceErrorMapsAreViewsOfTheGridThatAClickProbes) {
  const std::string out = (dir_ / "reference_error").string();
  startViewer({"builtin:temple", "--size", "160x90", "--time", "1.5", "--paused", "--reduce-while-moving", "off",
               "--probe-log", (dir_ / "probe.jsonl").string(), "--reference-error", out});
  const json done = waitEvent([](const json& j) { return j["event"] == "reference_error"; }, 120.0);
  ASSERT_FALSE(done.is_null()) << "no reference error; see " << (dir_ / "viewer.log");
  EXPECT_EQ(done["rows"], done["rows_expected"]) << "the progress did not count every row it expected";
  xdotool("key --window " + wid_ + " 1");
  const std::vector<std::string> maps = {"error/shadow", "error/silhouettes", "error/normal", "error/hdr",
                                         "error/position", "error/lighting", "decompose/lighting", "decompose/diffuse",
                                         "decompose/specular", "decompose/sun", "decompose/point_lights", "decompose/light_count"};
  const json grid = waitEvent(
      [&](const json& j) {
        if (j["event"] != "layout") return false;
        size_t found = 0;
        for (const json& v : j["views"]) found += std::count(maps.begin(), maps.end(), v["view"].get<std::string>());
        return found == maps.size();
      },
      90.0);
  ASSERT_FALSE(grid.is_null()) << "the grid never showed every reference map";
  std::string error;
  gui::Screenshot shot;
  EXPECT_TRUE(gui::screenshot(xvfb_.display, (dir_ / "grid.png").string(), shot, error)) << error;

  json count;
  for (const json& v : grid["views"])
    if (v["view"] == "decompose/light_count") count = v;
  const int px = 100, py = 70;  // the floor in front of the temple, under a few lights
  const auto [sx, sy] = screenOf(count, px, py);
  xdotool("mousemove --window " + wid_ + " " + std::to_string(sx) + " " + std::to_string(sy) + " click 1");
  const json probe = waitEvent([](const json& j) { return j["event"] == "probe"; });
  ASSERT_FALSE(probe.is_null()) << "the click produced no dossier";
  EXPECT_EQ(probe["pixel"], json({px, py}));
  const json hover = findEvent([](const json& j) { return j["event"] == "hover" && j["view"] == "decompose/light_count"; });
  ASSERT_FALSE(hover.is_null()) << "hovering the map shows no value";
  waitEvent([](const json& j) { return j["event"] == "probe_shown"; });  // the panel shows the dossier
  gui::screenshot(xvfb_.display, (dir_ / "probed.png").string(), shot, error);
  quit();

  size_t cursor = 0;
  const json dossier = gui::waitForLine((dir_ / "probe.jsonl").string(), 5.0, [](const json&) { return true; }, cursor);
  ASSERT_FALSE(dossier.is_null());
  EXPECT_EQ(dossier["pixel"], json({px, py}));
  int within = 0;
  for (const json& l : dossier["lighting"]["point_lights"]) within += l["distance"].get<double>() < l["radius"].get<double>();
  EXPECT_GT(within, 0) << "pick a pixel some light reaches";
  EXPECT_EQ(hover["text"], "decompose/light_count: " + std::to_string(within) + " point lights");
}

// Escape cancels the reference error while it runs: it stops (its last progress short of 100 %),
// writes nothing, and the viewer goes on.
TEST_F(GuiCompareTest, EscapeCancelsTheReferenceErrorWithNothingWritten) {
  const std::string out = (dir_ / "reference_error").string();
  startViewer({"builtin:temple", "--size", "480x480", "--time", "1.5", "--paused", "--reduce-while-moving", "off",
               "--reference-error", out});
  const json running = waitEvent([](const json& j) { return j["event"] == "reference_error_progress"; }, 60.0);
  ASSERT_FALSE(running.is_null()) << "no progress; see " << (dir_ / "viewer.log");
  xdotool("key --window " + wid_ + " Escape");
  const json cancelled = waitEvent([](const json& j) {
    return j["event"] == "reference_error_cancelled" || j["event"] == "reference_error";
  }, 60.0);
  ASSERT_FALSE(cancelled.is_null());
  ASSERT_EQ(cancelled["event"], "reference_error_cancelled") << "the work finished before the cancel";
  EXPECT_GT(cancelled["fraction"].get<double>(), 0.0);
  EXPECT_LT(cancelled["fraction"].get<double>(), 1.0);
  std::this_thread::sleep_for(std::chrono::milliseconds(500));  // the panel says so
  gui::Screenshot shot;
  std::string error;
  gui::screenshot(xvfb_.display, (dir_ / "cancelled.png").string(), shot, error);
  quit();
  EXPECT_FALSE(fs::exists(out)) << "a cancelled computation wrote its maps";
  EXPECT_FALSE(fs::exists(out + ".tmp-reference-error"));
}

}  // namespace gb
