// The viewer on an imported G-buffer, as a person uses it: a capture in a third-party layout (its
// own target names, base colour, world-space normals stored unorm x2-1, linear eye depth, object
// ids), opened with `gblens view --capture` under Xvfb. The grid shows exactly the layout's quantities;
// hover shows the stored codes; a click probes the pixel and the dossier holds the decoded values, checked against the analytic scene the frame was made from (a plane y = 0 seen
// from above at an angle: every value known in closed form).
#include "tests/support/test_paths.h"
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <algorithm>
#include <map>
#include <thread>
#include <chrono>

#include <glm/gtc/matrix_transform.hpp>

#include "renderer/core/layout_json.h"
#include "tests/gui/gpu_session.h"
#include "tests/gui/gui_util.h"
#include "views/capture/capture.h"
#include "views/import/import.h"

namespace gb {

namespace fs = std::filesystem;

namespace {

constexpr uint32_t kW = 160, kH = 90;

// The layout a user would write for their renderer (docs/layout-format.md), with its camera: a
// Vulkan projection (fov 60 degrees, near 0.5, far 50) looking at the plane y = 0 from (0, 4, 6).
nlohmann::json layoutJsonText() {
  return nlohmann::json::parse(R"({
    "format": "gblens-layout", "version": 1, "name": "analytic plane", "size": [160, 90],
    "targets": [
      {"name": "gbuf_color", "format": "rgba8_unorm",
       "quantities": [{"name": "BaseColor", "quantity": "base_color", "channels": [0, 1, 2]},
                      {"name": "Roughness", "quantity": "roughness", "channels": [3]}]},
      {"name": "gbuf_normal", "format": "rgba16_unorm",
       "quantities": [{"name": "N", "quantity": "normal", "encoding": "xyz_unorm", "space": "world", "channels": [0, 1, 2]}]},
      {"name": "lineardepth", "format": "r32f",
       "quantities": [{"name": "Z", "quantity": "depth", "encoding": "eye", "channels": [0]}]},
      {"name": "objects", "format": "r32_uint",
       "quantities": [{"name": "Object", "quantity": "id", "channels": [0], "names": {"1": "left tiles", "2": "right tiles"}}]}
    ]
  })");
}

}  // namespace

class GuiImportTest : public GpuGuiTest {
 protected:
  std::string folderPrefix() const override { return "gui_import_test/"; }

  // `gblens view --capture CAPTURE` (events in dir_/events.jsonl, `extra` after), awaited until it
  // presents the capture; the window's id, "" when it did not come up.
  std::string openViewer(const std::string& capture, const std::vector<std::string>& extra = {}) {
    std::vector<std::string> args = {GBLENS_BINARY, "view", "--capture", capture, "--validate", "--window", "1280x720",
                                     "--event-log", (dir_ / "events.jsonl").string()};
    args.insert(args.end(), extra.begin(), extra.end());
    viewer_ = gui::spawn(args, {"DISPLAY=" + xvfb_.display}, (dir_ / "viewer.log").string());
    if (waitEvent([](const nlohmann::json& j) { return j["event"] == "ready"; }, 60.0).is_null()) return "";
    const std::string wid = xdotool("search --onlyvisible --name '^gblens'");
    return wid.substr(0, wid.find('\n'));
  }
  // A capture opens on its layout's first colour view alone: the latest layout event saying so (the
  // window may have settled after the first one); null when there is none.
  nlohmann::json baseColorAlone() {
    size_t fromStart = 0;
    nlohmann::json one;
    auto alone = [](const nlohmann::json& j) {
      return j["event"] == "layout" && j["views"].size() == 1 && j["views"][0]["view"] == "BaseColor";
    };
    for (nlohmann::json j; !(j = gui::waitForLine((dir_ / "events.jsonl").string(), one.is_null() ? 30.0 : 1.0, alone,
                                                   fromStart)).is_null();)
      one = j;
    return one;
  }
};

// The analytic frame: eye position, the camera, and for each pixel the plane point it sees.
struct PlaneScene {
  Camera camera;
  glm::dvec3 eyeWorld{0.0, 4.0, 6.0};
  PlaneScene() {
    camera.width = kW;
    camera.height = kH;
    camera.eyeFromWorld = glm::lookAt(eyeWorld, glm::dvec3(0.0), glm::dvec3(0.0, 1.0, 0.0));
    camera.worldFromEye = glm::inverse(camera.eyeFromWorld);
    camera.clipFromEye = perspective(glm::radians(60.0), double(kW) / kH, 0.5, 50.0, false);
    camera.eyeFromClip = glm::inverse(camera.clipFromEye);  // a manifest's matrices agree (or it is refused)
    camera.clipFromWorld = camera.clipFromEye * camera.eyeFromWorld;
    camera.znear = 0.5;
    camera.zfar = 50.0;
  }
  // Eye depth of the plane at pixel (x, y), or nothing where the ray misses it (the sky).
  std::optional<double> eyeDepth(uint32_t x, uint32_t y) const {
    glm::dvec3 dirEye = eyeFromEyeDepth(camera, x, y, 1.0);  // at eye depth 1
    glm::dvec3 dirWorld = glm::dvec3(camera.worldFromEye * glm::dvec4(dirEye, 0.0));
    if (dirWorld.y >= -1e-9) return std::nullopt;
    return -eyeWorld.y / dirWorld.y;  // eye depth = the ray parameter, since dirEye.z = -1
  }
  glm::dvec3 baseColor(uint32_t x, uint32_t y) const { return {(x + 0.5) / kW, (y + 0.5) / kH, 0.25}; }
};

// The imported frame, built as gblens import builds one, written as a capture in `dir`.
static std::string writePlaneCapture(const fs::path& dir, const PlaneScene& scene) {
  // The layout parsed, the camera turned into gblens's convention, each target's texels as the
  // renderer would have stored them.
  Layout layout;
  std::string error;
  if (!parseLayout(layoutJsonText(), "analytic.json", layout, error)) throw std::runtime_error(error);
  FrameSnapshot f;
  f.setLayout(layout);
  f.camera = scene.camera;
  f.options.width = kW;
  f.options.height = kH;
  f.layout.camera.present = true;
  f.layout.camera.viewFromWorld = scene.camera.eyeFromWorld;
  f.layout.camera.clipFromView = scene.camera.clipFromEye;
  for (size_t t = 0; t < f.images.size(); ++t) {
    TargetImage& ti = f.images[t];
    describeImage(f.layout.targets[t], ti.image);
    ti.image.width = ti.targetWidth = kW;
    ti.image.height = ti.targetHeight = kH;
    ti.image.data.assign(size_t(kW) * kH * ti.image.texelBytes(), 0);
    f.absences[t] = Absent::No;
  }
  auto put = [&](int t, uint32_t x, uint32_t y, uint32_t c, auto v) {
    CpuImage& img = f.images[size_t(t)].image;
    std::memcpy(img.data.data() + (size_t(y) * kW + x) * img.texelBytes() + c * pixelTypeSize(img.type), &v, sizeof v);
  };
  for (uint32_t y = 0; y < kH; ++y)
    for (uint32_t x = 0; x < kW; ++x) {
      glm::dvec3 c = scene.baseColor(x, y);
      for (uint32_t k = 0; k < 3; ++k) put(0, x, y, k, uint8_t(std::lround(c[int(k)] * 255.0)));
      put(0, x, y, 3, uint8_t(128));
      std::optional<double> z = scene.eyeDepth(x, y);
      if (!z) continue;
      // World normal (0, 1, 0) stored unorm: n * 0.5 + 0.5.
      for (uint32_t k = 0; k < 3; ++k) put(1, x, y, k, uint16_t(k == 1 ? 65535 : 32768));
      put(2, x, y, 0, float(*z));
      put(3, x, y, 0, uint32_t(x < kW / 2 ? 1 : 2));
    }
  const std::string capture = (dir / "imported").string();
  if (!writeCapture(capture, f, CaptureMeta{}, error)) throw std::runtime_error(error);
  return capture;
}

TEST_F(GuiImportTest, AnImportedCaptureShowsItsViewsAndAClickProbesItsDecodedValues) {
  PlaneScene scene;
  std::string error;
  const std::string capture = writePlaneCapture(dir_, scene);

  const std::string wid = openViewer(capture, {"--probe-log", (dir_ / "probe.jsonl").string()});
  ASSERT_FALSE(wid.empty()) << "the viewer did not present the capture; see " << (dir_ / "viewer.log");
  int winX = 0, winY = 0;
  std::string geometry = xdotool("getwindowgeometry " + wid);
  std::sscanf(geometry.c_str() + geometry.find("Position:"), "Position: %d,%d", &winX, &winY);

  // The grid: exactly the layout's quantities, none of gblens's own (no shadow, specular, stencil or
  // coverage stand-ins), the first colour quantity first.
  xdotool("key --window " + wid + " 1");
  nlohmann::json grid = waitEvent([](const nlohmann::json& j) { return j["event"] == "layout" && j["views"].size() > 1; });
  ASSERT_FALSE(grid.is_null());
  gui::Screenshot shot;
  ASSERT_TRUE(gui::screenshot(xvfb_.display, (dir_ / "grid.png").string(), shot, error)) << error;
  std::vector<std::string> shown, declared;
  std::map<std::string, nlohmann::json> views;
  for (const nlohmann::json& v : grid["views"]) {
    shown.push_back(v["view"]);
    views[v["view"]] = v;
    EXPECT_FALSE(v.contains("unavailable")) << v.dump();
  }
  const nlohmann::json layout = layoutJsonText();
  for (const nlohmann::json& t : layout["targets"])
    for (const nlohmann::json& q : t["quantities"]) declared.push_back(q["name"]);
  EXPECT_EQ(shown.front(), "BaseColor");
  std::sort(shown.begin(), shown.end());
  std::sort(declared.begin(), declared.end());
  EXPECT_EQ(shown, declared);
  // The base colour view shows its gradient: red grows to the right.
  const nlohmann::json& a = views["BaseColor"];
  auto screenAt = [&](const nlohmann::json& v, double px, double py) {
    double sx = double(v["origin"][0]) + px * double(v["scale"]) + winX;
    double sy = double(v["origin"][1]) + py * double(v["scale"]) + winY;
    return shot.at(int(sx), int(sy));
  };
  EXPECT_LT(screenAt(a, 20, 60)[0] + 0.2f, screenAt(a, 140, 60)[0]) << "base colour: no red gradient";

  // The base colour alone (key 0: the first view), then the mouse over a pixel of the plane: the
  // status bar's stored values are the texel's codes as written, the decoded ones its colour.
  xdotool("key --window " + wid + " 0");
  nlohmann::json one = waitEvent([](const nlohmann::json& j) {
    return j["event"] == "layout" && j["views"].size() == 1 && j["views"][0]["view"] == "BaseColor";
  });
  ASSERT_FALSE(one.is_null());
  const nlohmann::json& v = one["views"][0];
  const uint32_t px = 40, py = 70;
  ASSERT_TRUE(scene.eyeDepth(px, py).has_value());
  double sx = double(v["origin"][0]) + (px + 0.5) * double(v["scale"]);
  double sy = double(v["origin"][1]) + (py + 0.5) * double(v["scale"]);
  xdotool("mousemove --window " + wid + " " + std::to_string(int(sx)) + " " + std::to_string(int(sy)));
  nlohmann::json hover = waitEvent([](const nlohmann::json& j) {
    return j["event"] == "hover" && j["text"].get<std::string>().rfind("BaseColor (40, 70)", 0) == 0;
  });
  ASSERT_FALSE(hover.is_null()) << "no hover text";
  const glm::dvec3 c = scene.baseColor(px, py);
  const std::string stored = "BaseColor (40, 70)  stored gbuf_color (rgba8_unorm) BaseColor.R " +
                             std::to_string(std::lround(c.x * 255.0)) + " BaseColor.G " + std::to_string(std::lround(c.y * 255.0)) +
                             " BaseColor.B " + std::to_string(std::lround(c.z * 255.0));
  EXPECT_EQ(hover["text"].get<std::string>().rfind(stored, 0), 0u) << hover["text"] << "\nexpected to start with " << stored;
  xdotool("click 1");
  ASSERT_FALSE(waitEvent([](const nlohmann::json& j) { return j["event"] == "probe_shown"; }).is_null());
  std::this_thread::sleep_for(std::chrono::milliseconds(800));  // the panel's tables settle their widths
  ASSERT_TRUE(gui::screenshot(xvfb_.display, (dir_ / "probe.png").string(), shot, error)) << error;
  size_t cursor = 0;
  nlohmann::json d = gui::waitForLine((dir_ / "probe.jsonl").string(), 5.0, [](const nlohmann::json&) { return true; }, cursor);
  ASSERT_FALSE(d.is_null());
  EXPECT_EQ(d["pixel"], nlohmann::json({px, py}));
  std::map<std::string, nlohmann::json> q;
  for (const nlohmann::json& e : d["quantities"]) q[e["name"]] = e;
  // Base colour: 8-bit unorm, within half a step of the analytic value.
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(q["BaseColor"]["values"][k].get<double>(), scene.baseColor(px, py)[k], 0.5 / 255.0 + 1e-9);
  // The normal in the space the layout stores it in (world): +Y, unit length within the 16-bit unorm step.
  EXPECT_EQ(q["N"]["space"], "world (layout: Y-up)");
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(q["N"]["values"][k].get<double>(), k == 1 ? 1.0 : 0.0, 2.0 / 65535.0);
  // Only the layout's quantities: nothing of gblens's own frame (decoded G-buffer, shadow map, hdr).
  for (const char* gblensOnly : {"shadow_map", "hdr", "final"})  // one shape for every layout: null here
    EXPECT_TRUE(d.contains(gblensOnly) && d[gblensOnly].is_null()) << gblensOnly;
  // Eye depth as stored (float) and the position reconstructed from it on the plane y = 0.
  const double z = *scene.eyeDepth(px, py);
  EXPECT_NEAR(q["Z"]["values"][0].get<double>(), z, z * 1e-7);
  bool reconstructed = false;
  for (const nlohmann::json& r : d["reconstructions"])
    if (r["quantity"] == "Z" && r["valid"].get<bool>()) {
      reconstructed = true;
      EXPECT_NEAR(r["world"][1].get<double>(), 0.0, 1e-5);
    }
  EXPECT_TRUE(reconstructed);
  EXPECT_EQ(q["Object"]["values"][0].get<double>(), 1.0);
  EXPECT_EQ(q["Object"]["note"], "left tiles");
  EXPECT_FALSE(d["lighting"].value("note", "").empty()) << "an imported layout without lights says it did not evaluate them";

  xdotool("key --window " + wid + " ctrl+q");
  int status = -1;
  ASSERT_TRUE(gui::waitExit(viewer_, 30.0, status)) << "the viewer did not quit";
  viewer_ = -1;
  EXPECT_EQ(status, 0) << "validation messages or a failure; see " << (dir_ / "viewer.log");
}

}  // namespace gb

namespace gb {

// Region statistics as a person gets them: ctrl + drag over the albedo view of the imported frame
// selects the texels under the press and the release; the viewer's numbers (its event log holds
// what the Region panel shows) are those of `gblens stats` for that capture and rect, and the base
// colour's mean is the analytic one (8-bit steps of (x + 0.5) / 160).
TEST_F(GuiImportTest, ACtrlDragSelectsARegionWhoseStatisticsAreGblensStats) {
  PlaneScene scene;
  const std::string capture = writePlaneCapture(dir_, scene);
  const std::string wid = openViewer(capture);
  ASSERT_FALSE(wid.empty()) << "the viewer did not present the capture; see " << (dir_ / "viewer.log");
  const nlohmann::json one = baseColorAlone();
  ASSERT_FALSE(one.is_null());
  const nlohmann::json& v = one["views"][0];
  auto at = [&](uint32_t px, uint32_t py) {
    return std::to_string(int(double(v["origin"][0]) + (px + 0.5) * double(v["scale"]))) + " " +
           std::to_string(int(double(v["origin"][1]) + (py + 0.5) * double(v["scale"])));
  };
  const uint32_t x0 = 20, y0 = 50, x1 = 59, y1 = 79;  // both corners included: 40 x 30
  xdotool("mousemove --window " + wid + " " + at(x0, y0) + " sleep 0.2 keydown ctrl sleep 0.2 mousedown 1 sleep 0.2" +
          " mousemove --window " + wid + " " + at((x0 + x1) / 2, (y0 + y1) / 2) + " sleep 0.2 mousemove --window " + wid +
          " " + at(x1, y1) + " sleep 0.3 mouseup 1 sleep 0.2 keyup ctrl");
  nlohmann::json region = waitEvent([](const nlohmann::json& j) { return j["event"] == "region"; });
  ASSERT_FALSE(region.is_null()) << "no region event; see " << (dir_ / "viewer.log");
  const nlohmann::json& st = region["stats"];
  EXPECT_EQ(st["rect"], nlohmann::json({{"x", x0}, {"y", y0}, {"width", x1 - x0 + 1}, {"height", y1 - y0 + 1}}));
  gui::Screenshot shot;
  std::string error;
  ASSERT_TRUE(gui::screenshot(xvfb_.display, (dir_ / "region.png").string(), shot, error)) << error;

  // The same numbers from the command line.
  gui::run(std::string(GBLENS_BINARY) + " stats '" + capture + "' --rect 20,50,40,30 --json > '" +
           (dir_ / "stats.json").string() + "'");
  std::ifstream in(dir_ / "stats.json");
  const nlohmann::json cli = nlohmann::json::parse(in);
  EXPECT_EQ(st["channels"], cli["channels"]);
  EXPECT_EQ(st["quantities"], cli["quantities"]);
  // And from the analytic scene: the base colour's red mean over the rect, in 8-bit steps.
  double red = 0.0;
  for (uint32_t x = x0; x <= x1; ++x) red += std::lround(scene.baseColor(x, 0).x * 255.0) / 255.0;
  red /= double(x1 - x0 + 1);
  bool found = false;
  for (const nlohmann::json& q : st["quantities"])
    if (q["target"] == "gbuf_color" && q["series"] == "BaseColor.R") {
      found = true;
      EXPECT_NEAR(q["mean"].get<double>(), red, 1e-9);
      EXPECT_EQ(q["count"].get<uint64_t>(), 40u * 30u);  // every pixel of the rect sees the plane
    }
  EXPECT_TRUE(found) << st.dump();

  xdotool("key --window " + wid + " ctrl+q");
  int status = -1;
  ASSERT_TRUE(gui::waitExit(viewer_, 30.0, status)) << "the viewer did not quit";
  viewer_ = -1;
  EXPECT_EQ(status, 0) << "validation messages or a failure; see " << (dir_ / "viewer.log");
}

}  // namespace gb

namespace gb {

// Values in texels, as tev and RenderDoc print them: zoomed in on the imported plane with the wheel,
// each texel of the base colour shows its R, G, B as the 8-bit codes the test wrote decode (code / 255,
// four significant digits: an 8-bit step), and of the eye depth the float the test stored (seven
// digits); texels where nothing was drawn print nothing. Checked against the analytic scene, and
// screenshotted (zoom_basecolor.png, zoom_depth.png) for a person to read.
TEST_F(GuiImportTest, ZoomedInEachTexelPrintsItsValueAtItsStoragePrecision) {
  PlaneScene scene;
  std::string error;
  const std::string capture = writePlaneCapture(dir_, scene);
  const std::string wid = openViewer(capture);
  ASSERT_FALSE(wid.empty()) << "the viewer did not present the capture; see " << (dir_ / "viewer.log");
  auto alone = [&](const std::string& key, const std::string& name) {
    xdotool("key --window " + wid + " " + key);
    return waitEvent([name](const nlohmann::json& j) {
      return j["event"] == "layout" && j["views"].size() == 1 && j["views"][0]["view"] == name;
    });
  };
  const nlohmann::json one = baseColorAlone();
  ASSERT_FALSE(one.is_null());
  // The wheel over pixel (40, 70) of the plane until the values fit in the texels (at most 30 steps).
  const nlohmann::json& v = one["views"][0];
  const int sx = int(double(v["origin"][0]) + 40.5 * double(v["scale"]));
  const int sy = int(double(v["origin"][1]) + 70.5 * double(v["scale"]));
  xdotool("mousemove --window " + wid + " " + std::to_string(sx) + " " + std::to_string(sy));
  auto valuesOf = [](const std::string& name) {
    return [name](const nlohmann::json& j) { return j["event"] == "texel_values" && j["view"] == name && !j["texels"].empty(); };
  };
  nlohmann::json values;
  for (int step = 0; step < 30 && values.is_null(); ++step) {
    xdotool("click --window " + wid + " 4");
    values = waitEvent(valuesOf("BaseColor"), 1.0);
  }
  ASSERT_FALSE(values.is_null()) << "no values in texels after 30 wheel steps; see " << (dir_ / "events.jsonl");
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  gui::Screenshot shot;
  ASSERT_TRUE(gui::screenshot(xvfb_.display, (dir_ / "zoom_basecolor.png").string(), shot, error)) << error;
  EXPECT_GE(values["scale"].get<double>(), 40.0);
  bool sawHovered = false;
  for (const nlohmann::json& t : values["texels"]) {
    const uint32_t x = t["texel"][0], y = t["texel"][1];
    sawHovered |= x == 40 && y == 70;
    const glm::dvec3 c = scene.baseColor(x, y);
    std::vector<std::string> expected;
    for (int k = 0; k < 3; ++k) {
      char line[32];
      std::snprintf(line, sizeof line, "%c %.4g", "RGB"[k], double(std::lround(c[k] * 255.0)) / 255.0);
      expected.push_back(line);
    }
    EXPECT_EQ(t["lines"].get<std::vector<std::string>>(), expected) << "texel " << x << "," << y;
  }
  EXPECT_TRUE(sawHovered) << "the texel under the mouse was not among those printed";

  // The eye depth at the same zoom: the stored float, seven digits; the sky (no surface) prints nothing.
  const nlohmann::json zLayout = alone("4", "Z");
  ASSERT_FALSE(zLayout.is_null());
  nlohmann::json depth = waitEvent(valuesOf("Z"), 10.0);
  ASSERT_FALSE(depth.is_null());
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  ASSERT_TRUE(gui::screenshot(xvfb_.display, (dir_ / "zoom_depth.png").string(), shot, error)) << error;
  // The depth's legend lies in a strip below the image, never on it: zoomed in, the image fills its
  // rectangle and stops at the strip, whose pixels right of the legend box are the strip's grey.
  {
    int winX = 0, winY = 0;
    const std::string geometry = xdotool("getwindowgeometry " + wid);
    std::sscanf(geometry.c_str() + geometry.find("Position:"), "Position: %d,%d", &winX, &winY);
    const nlohmann::json& zv = zLayout["views"][0];
    const double imageBottom = double(zv["image_rect"][1]) + double(zv["image_rect"][3]);
    const double slotBottom = double(zv["rect"][1]) + double(zv["rect"][3]);
    ASSERT_GT(slotBottom - imageBottom, 30.0) << "no legend strip below the image: " << zv.dump();
    const int right = int(double(zv["rect"][0]) + double(zv["rect"][2])) - 6;
    for (int y = int(imageBottom) + 2; y < int(slotBottom) - 2; y += 4)
      for (int x = right - 60; x < right; x += 6) {
        const float* p = shot.at(x + winX, y + winY);
        EXPECT_NEAR(p[0], 0.08f, 0.03f) << "the strip at " << x << "," << y << " is not the legend's background";
      }
    // ... and the image's last row above it is the picture (the plane's depths, not the strip).
    const float* above = shot.at(right - 30 + winX, int(imageBottom) - 3 + winY);
    EXPECT_GT(std::abs(above[0] - 0.08f), 0.05f) << "the image does not reach its strip";
  }
  for (const nlohmann::json& t : depth["texels"]) {
    const uint32_t x = t["texel"][0], y = t["texel"][1];
    const std::optional<double> z = scene.eyeDepth(x, y);
    ASSERT_TRUE(z.has_value()) << "a value printed where nothing was drawn: " << x << "," << y;
    char line[32];
    std::snprintf(line, sizeof line, "%.7g", double(float(*z)));
    EXPECT_EQ(t["lines"], nlohmann::json::array({line})) << "texel " << x << "," << y;
  }

  xdotool("key --window " + wid + " ctrl+q");
  int status = -1;
  ASSERT_TRUE(gui::waitExit(viewer_, 30.0, status)) << "the viewer did not quit";
  viewer_ = -1;
  EXPECT_EQ(status, 0) << "validation messages or a failure; see " << (dir_ / "viewer.log");
}

}  // namespace gb
