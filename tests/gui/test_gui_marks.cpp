// Shadow-map marks as a person meets them (issue 37): a 1920x1080 frame fitted into a 1280x720 window
// (under a screen pixel per texel), a click on a shadow-map texel that `gblens probe` says a pixel's
// lookup reads; the Final view then shows the marked pixels' box in magenta at fit zoom, the event log
// counts them with a box holding that pixel, M zooms every view to the box, and a texel no lookup
// reads says why none are marked. And the live frame zoomed in prints each texel's value, read back
// from the GPU, as a capture of the same frame gives it.
#include "tests/support/test_paths.h"
#include <gtest/gtest.h>

#include <string>

#include "tests/gui/gpu_session.h"
#include "views/analysis/view_table.h"
#include "views/analysis/view_text.h"
#include "views/analysis/visualize.h"
#include "views/capture/capture.h"

namespace gb {
namespace {

using json = nlohmann::json;

class GuiMarksTest : public GpuGuiTest {
 protected:
  std::string folderPrefix() const override { return "gui_test/"; }
  json waitLayout(const std::string& view) {
    return waitEvent([&](const json& j) { return j["event"] == "layout" && j["views"].size() == 1 && j["views"][0]["view"] == view; }, 60.0);
  }
  void clickTexel(const json& view, double x, double y) {
    const int sx = int(double(view["origin"][0]) + x * double(view["scale"]));
    const int sy = int(double(view["origin"][1]) + y * double(view["scale"]));
    xdotool("mousemove --window " + wid_ + " " + std::to_string(sx) + " " + std::to_string(sy) + " click 1");
    xdotool("mousemove --window " + wid_ + " 640 715");
  }
};

// Magenta screen pixels inside a rectangle of the screenshot.
int magentaPixels(const gui::Screenshot& s, int x0, int y0, int x1, int y1) {
  int n = 0;
  for (int y = std::max(0, y0); y < std::min(s.height, y1); ++y)
    for (int x = std::max(0, x0); x < std::min(s.width, x1); ++x) {
      const float* p = s.at(x, y);
      n += p[0] > 0.8f && p[1] < 0.3f && p[2] > 0.8f;
    }
  return n;
}

TEST_F(GuiMarksTest, AClickedShadowTexelMarksItsPixelsVisiblyAndMZoomsToThem) {
  const std::string frame = "--size 1920x1080 --time 1.5 --shadow-map-size 256";
  const int px = 1040, py = 800;  // the floor in front of the temple
  const std::string capture = (dir_ / "capture").string();
  int status = -1;
  gui::run(std::string(GBLENS_BINARY) + " capture builtin:temple " + frame + " -o " + capture + " 2>&1", &status);
  ASSERT_EQ(status, 0);
  const json probe = json::parse(gui::run(std::string(GBLENS_BINARY) + " probe " + capture + " " + std::to_string(px) + " " +
                                          std::to_string(py) + " --json", &status));
  ASSERT_EQ(status, 0);
  const json texel = probe["shadow_map"]["texels"][0]["texel"];  // the 2x2 block's first: this pixel reads it

  startViewer({"builtin:temple", "--size", "1920x1080", "--time", "1.5", "--shadow-map-size", "256", "--paused",
               "--reduce-while-moving", "off"});
  xdotool("key --window " + wid_ + " 9");
  const json shadow = waitLayout("ShadowMap");
  ASSERT_FALSE(shadow.is_null());
  clickTexel(shadow["views"][0], double(texel[0]) + 0.5, double(texel[1]) + 0.5);
  const json mark = waitEvent([](const json& j) { return j["event"] == "shadow_mark"; }, 60.0);
  ASSERT_FALSE(mark.is_null()) << "the click marked nothing";
  EXPECT_EQ(mark["texel"], texel);
  ASSERT_GT(mark["pixels"].get<int>(), 0) << mark.dump();
  const json box = mark["box"];
  EXPECT_TRUE(px >= box[0] && px < int(box[0]) + int(box[2]) && py >= box[1] && py < int(box[1]) + int(box[3]))
      << "the probed pixel reads the texel, so it lies in the marks' box: " << box.dump();

  // At fit zoom (about 0.6 screen pixels per texel) the box is drawn at least 12 pixels wide.
  xdotool("key --window " + wid_ + " 0");
  const json fit = waitLayout("Final");
  ASSERT_FALSE(fit.is_null());
  const json& v = fit["views"][0];
  const double s = v["scale"], ox = v["origin"][0], oy = v["origin"][1];
  ASSERT_LT(s, 1.0) << "the frame is larger than its view";
  const double cx = ox + (double(box[0]) + double(box[2]) / 2) * s, cy = oy + (double(box[1]) + double(box[3]) / 2) * s;
  const double half = std::max(double(box[2]), double(box[3])) * s / 2 + 12;
  gui::Screenshot before;
  std::string error;
  ASSERT_TRUE(gui::screenshot(xvfb_.display, (dir_ / "marks_fit.png").string(), before, error)) << error;
  EXPECT_GE(magentaPixels(before, int(cx - half), int(cy - half), int(cx + half), int(cy + half)), 4 * 12)
      << "no magenta box around the marked pixels at fit zoom (marks_fit.png)";

  // M: the views frame the box, centred, zoomed in.
  xdotool("key --window " + wid_ + " m");
  const json zoomed = waitEvent([&](const json& j) {
    return j["event"] == "layout" && j["views"].size() == 1 && double(j["views"][0]["scale"]) > 2 * s;
  });
  ASSERT_FALSE(zoomed.is_null()) << "M did not zoom";
  const json& z = zoomed["views"][0];
  const double zs = z["scale"];
  const double zx = double(z["origin"][0]) + (double(box[0]) + double(box[2]) / 2) * zs;
  const double zy = double(z["origin"][1]) + (double(box[1]) + double(box[3]) / 2) * zs;
  const double midX = double(z["image_rect"][0]) + double(z["image_rect"][2]) / 2, midY = double(z["image_rect"][1]) + double(z["image_rect"][3]) / 2;
  EXPECT_NEAR(zx, midX, 2.0) << "the box is centred";
  EXPECT_NEAR(zy, midY, 2.0);
  gui::Screenshot after;
  ASSERT_TRUE(gui::screenshot(xvfb_.display, (dir_ / "marks_zoomed.png").string(), after, error)) << error;

  // A texel at the shadow map's corner: no pixel's lookup reads it, and the log says why.
  xdotool("key --window " + wid_ + " 9");
  xdotool("key --window " + wid_ + " z");
  const json again = waitEvent([](const json& j) {
    return j["event"] == "layout" && j["views"].size() == 1 && j["views"][0]["view"] == "ShadowMap" && double(j["views"][0]["scale"]) < 4;
  });
  ASSERT_FALSE(again.is_null());
  clickTexel(again["views"][0], 1.5, 1.5);
  const json none = waitEvent([](const json& j) { return j["event"] == "shadow_mark" && j["texel"] == json({1, 1}); }, 60.0);
  ASSERT_FALSE(none.is_null());
  EXPECT_EQ(none["pixels"], 0);
  EXPECT_NE(none.value("note", "").find("no pixel's lookup reads it"), std::string::npos) << none.dump();
  quit();
}

TEST_F(GuiMarksTest, TheLiveFrameZoomedInPrintsEachTexelsValueAsItsCaptureHasIt) {
  const std::string capture = (dir_ / "capture").string();
  int status = -1;
  gui::run(std::string(GBLENS_BINARY) + " capture builtin:temple --size 192x108 --time 1.5 -o " + capture + " 2>&1", &status);
  ASSERT_EQ(status, 0);
  Capture c;
  std::string error;
  ASSERT_TRUE(loadCapture(capture, c, error)) << error;
  const std::vector<ViewDef> views = layoutViews(c.frame.layout);

  startViewer({"builtin:temple", "--size", "192x108", "--time", "1.5", "--paused", "--reduce-while-moving", "off"});
  for (const auto& [key, name] : {std::pair<std::string, std::string>{"6", "Depth"}, {"4", "Normal"}}) {
    SCOPED_TRACE(name);
    xdotool("key --window " + wid_ + " " + key);
    const json layout = waitLayout(name);
    ASSERT_FALSE(layout.is_null());
    if (name == "Depth") {  // the wheel over texel (104, 80) until values fit (the zoom is shared)
      const json& v = layout["views"][0];
      const int sx = int(double(v["origin"][0]) + 104.5 * double(v["scale"])), sy = int(double(v["origin"][1]) + 80.5 * double(v["scale"]));
      xdotool("mousemove --window " + wid_ + " " + std::to_string(sx) + " " + std::to_string(sy));
    }
    json values;
    for (int step = 0; step < 30 && values.is_null(); ++step) {
      xdotool("click --window " + wid_ + " 4");  // normals need more room (three lines) than depths
      values = waitEvent([&](const json& j) { return j["event"] == "texel_values" && j["view"] == name && !j["texels"].empty(); }, 1.5);
    }
    ASSERT_FALSE(values.is_null()) << "no values in the live frame's texels";
    const ViewDef& def = views[size_t(findView(views, name))];
    int checked = 0;
    for (const json& t : values["texels"]) {
      const uint32_t x = t["texel"][0], y = t["texel"][1];
      const std::vector<std::string> want = texelValueLines(c.frame, def, viewValue(c.frame, def, x, y), 0xF);
      EXPECT_EQ(t["lines"].get<std::vector<std::string>>(), want) << "texel " << x << "," << y;
      ++checked;
    }
    EXPECT_GT(checked, 4);
  }
  gui::Screenshot shot;
  ASSERT_TRUE(gui::screenshot(xvfb_.display, (dir_ / "live_values.png").string(), shot, error)) << error;
  quit();
}

}  // namespace
}  // namespace gb
