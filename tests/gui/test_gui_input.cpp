// Input is never lost (issue 37): a key sent the moment the window exists (before its first frame
// is on screen), five arrow presses and a ctrl + drag sent at once while slow full frames render
// (1920x1080, animation playing, no reduction: a second or more per frame on lavapipe) each have
// their whole effect: the view the key asks for, the probe five pixels on, the region dragged.
#include "tests/support/test_paths.h"
#include <gtest/gtest.h>

#include <string>
#include <thread>

#include "tests/gui/gpu_session.h"

namespace gb {
namespace {

using json = nlohmann::json;

class GuiInputTest : public GpuGuiTest {
 protected:
  std::string folderPrefix() const override { return "gui_test/"; }
};

// The screen point of texel (x, y)'s centre in a view of a layout event, as "X Y".
std::string screenAt(const json& view, int x, int y) {
  return std::to_string(int(double(view["origin"][0]) + (x + 0.5) * double(view["scale"]))) + " " +
         std::to_string(int(double(view["origin"][1]) + (y + 0.5) * double(view["scale"])));
}

TEST_F(GuiInputTest, KeysAndDragsDuringSlowFramesAndAtStartUpAllTakeEffect) {
  const std::string log = (dir_ / "events.jsonl").string();
  xdotool("mousemove 2 718");
  viewer_ = gui::spawn({GBLENS_BINARY, "view", "builtin:temple", "--validate", "--size", "1920x1080", "--window", "1280x720",
                        "--reduce-while-moving", "off", "--event-log", log},
                       {"DISPLAY=" + xvfb_.display}, (dir_ / "viewer.log").string());
  // At start-up: the key as soon as the window is there.
  std::string wid;
  for (int i = 0; i < 600 && wid.empty(); ++i) {
    wid = xdotool("search --onlyvisible --name '^gblens'");
    wid = wid.substr(0, wid.find('\n'));
    if (wid.empty()) std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  ASSERT_FALSE(wid.empty()) << "no window; see " << (dir_ / "viewer.log");
  xdotool("key --window " + wid + " 4");
  size_t cursor = 0;
  const bool beforeFirstFrame = gui::waitForLine(log, 0.0, [](const json& j) { return j["event"] == "ready"; }, cursor).is_null();
  const json normal = waitEvent([](const json& j) {
    return j["event"] == "layout" && j["views"].size() == 1 && j["views"][0]["view"] == "Normal";
  }, 90.0);
  ASSERT_FALSE(normal.is_null()) << "the key sent at start-up was lost (sent before the first frame: " << beforeFirstFrame << ")";
  ASSERT_FALSE(findEvent([](const json& j) { return j["event"] == "ready"; }, 60.0).is_null());

  // A probe, then five arrow presses at once while frames render.
  const json& view = normal["views"][0];
  ASSERT_LT(double(view["scale"]), 1.0);
  const int px = 900, py = 700;
  xdotool("mousemove --window " + wid + " " + screenAt(view, px, py) + " click 1 mousemove --window " + wid + " 640 715");
  const json first = waitEvent([](const json& j) { return j["event"] == "probe"; }, 60.0);
  ASSERT_FALSE(first.is_null());
  const int x0 = first["pixel"][0], y0 = first["pixel"][1];
  const double slack = 1.0 / double(view["scale"]) + 1;  // a screen pixel covers several texels
  EXPECT_NEAR(x0, px, slack);
  EXPECT_NEAR(y0, py, slack);
  // 10 ms apart: faster than anyone types, far inside one frame. (Not 0: GLFW drops a second press
  // of a key stamped in the same millisecond as the first, taking it for an input method's duplicate.)
  xdotool("key --window " + wid + " --delay 10 Right Right Right Right Right");
  const json moved = waitEvent([&](const json& j) { return j["event"] == "probe" && j["pixel"] == json({x0 + 5, y0}); }, 60.0);
  EXPECT_FALSE(moved.is_null()) << "an arrow press was lost: the probe did not reach (" << x0 + 5 << ", " << y0 << ")";

  // A ctrl + drag faster than a frame: the region from its first corner to its last.
  xdotool("mousemove --window " + wid + " " + screenAt(view, 300, 200) + " keydown ctrl mousedown 1 mousemove --window " + wid +
          " " + screenAt(view, 500, 350) + " mouseup 1 keyup ctrl mousemove --window " + wid + " 640 715");
  // (The frames that come while the button is down count the region as far as it goes: its first texel.)
  const json region = waitEvent([](const json& j) { return j["event"] == "region" && j["stats"]["rect"]["width"] > 1; }, 90.0);
  ASSERT_FALSE(region.is_null()) << "the drag was lost: only its first corner was seen";
  const json rect = region["stats"]["rect"];
  EXPECT_NEAR(int(rect["x"]), 300, slack);
  EXPECT_NEAR(int(rect["y"]), 200, slack);
  EXPECT_NEAR(int(rect["width"]), 201, 2 * slack);
  EXPECT_NEAR(int(rect["height"]), 151, 2 * slack);
  wid_ = wid;
  quit();
}

}  // namespace
}  // namespace gb
