// The timeline on an attached application's kept frames, as a person uses it: `gblens attach --layout
// L --history 4 -- APP` under Xvfb (APP: tests/subjects/foreign_deferred, as test_gui_attach.cpp).
// Live, the strip sits on the newest frame; Space freezes the stream on the newest kept frame (the
// four kept frames' application numbers in the log); `,` `,` steps back two kept frames, shown as a
// streamed frame is (no frame is taken from the stream meanwhile); a click probes that frame and the
// probe's track lists the four kept frames; Space returns to the stream, whose next frame is newer
// than every kept one; `,` on the running stream freezes it again (its newer kept frames, the probe
// tracked over them at once) and steps back one.
#include "tests/support/test_paths.h"
#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <cmath>
#include <thread>

#include "tests/gui/attach_session.h"
#include "tests/gui/gui_util.h"

namespace gb {

using nlohmann::json;

TEST_F(GuiAttachTest, HistoryTimelineFreezesStepsBackAndTracksTheProbeOverTheKeptFrames) {
  startViewer("--frames 16384", "--layout live.json --history 4");
  ASSERT_FALSE(waitEvent([](const json& j) { return j["event"] == "attach_frame" && j["received"] >= 6; }).is_null())
      << "the stream did not bring six frames";
  xdotool("key --window " + wid_ + " 1");
  const json grid = waitEvent([](const json& j) { return j["event"] == "layout" && j["views"].size() > 1; });
  ASSERT_FALSE(grid.is_null());
  json albedo;
  for (const json& v : grid["views"])
    if (v["view"] == "Albedo") albedo = v;
  ASSERT_FALSE(albedo.is_null());

  std::this_thread::sleep_for(std::chrono::milliseconds(800));  // the grid's views decoded (live: the strip on the newest)
  gui::Screenshot shot;
  std::string error;
  ASSERT_TRUE(gui::screenshot(xvfb_.display, (dir_ / "history_live.png").string(), shot, error)) << error;

  // Space: frozen on the newest kept frame, four kept (the bound: --history 4).
  xdotool("key --window " + wid_ + " space");
  const json frozen = waitEvent([](const json& j) { return j["event"] == "history_frame" && j["state"] == "frozen"; });
  ASSERT_FALSE(frozen.is_null()) << "Space did not freeze the strip on the kept frames";
  const json kept = frozen["frames"];
  ASSERT_EQ(kept.size(), 4u) << frozen.dump();
  EXPECT_EQ(frozen["limit"], 4);
  EXPECT_GT(frozen["bytes"].get<uint64_t>(), 0u);
  EXPECT_EQ(frozen["index"], 3);
  EXPECT_EQ(frozen["app_frame"], kept[3]);
  for (size_t i = 1; i < kept.size(); ++i) EXPECT_GT(kept[i].get<int64_t>(), kept[i - 1].get<int64_t>()) << kept.dump();

  // `,` twice: the kept frame two below the newest, its application frame number; nothing taken.
  xdotool("key --window " + wid_ + " comma comma");
  const json back = waitEvent([](const json& j) { return j["event"] == "history_frame" && j["index"] == 1; });
  ASSERT_FALSE(back.is_null()) << "`,` `,` did not step back two kept frames";
  EXPECT_EQ(back["app_frame"], kept[1]) << "kept " << kept.dump();
  EXPECT_EQ(back["frames"], kept) << "the kept frames changed while frozen";
  EXPECT_EQ(back["state"], "frozen");

  // A click probes the frame shown; its track goes over the four kept frames.
  const double ox = albedo["origin"][0], oy = albedo["origin"][1], scale = albedo["scale"];
  const uint32_t w = albedo["image"][0], h = albedo["image"][1];
  const int sx = int(std::floor(ox + (w / 2 + 0.5) * scale)), sy = int(std::floor(oy + (h * 2 / 3 + 0.5) * scale));
  xdotool("mousemove --window " + wid_ + " " + std::to_string(sx) + " " + std::to_string(sy) + " click 1");
  const json track = waitEvent([](const json& j) { return j["event"] == "track"; });
  ASSERT_FALSE(track.is_null()) << "the click on a frozen kept frame made no track";
  EXPECT_EQ(track["frames"], kept);
  EXPECT_EQ(track["start"], 1);
  ASSERT_EQ(track["texels"].size(), 4u) << track.dump();
  EXPECT_EQ(track["texels"][1], track["pixel"]);
  EXPECT_LE(track["first"].get<int>(), 1);
  EXPECT_GE(track["last"].get<int>(), 1);
  EXPECT_EQ(track["view"], "Albedo");
  std::printf("track over kept frames %s: first %d last %d texels %s\n", kept.dump().c_str(), track["first"].get<int>(),
              track["last"].get<int>(), track["texels"].dump().c_str());
  xdotool("mousemove --window " + wid_ + " 10 300");
  std::this_thread::sleep_for(std::chrono::milliseconds(800));  // the frame and strip on screen
  ASSERT_TRUE(gui::screenshot(xvfb_.display, (dir_ / "history_frozen.png").string(), shot, error)) << error;
  std::printf("screenshot: %s\n", (dir_ / "history_frozen.png").c_str());
  for (const json& e : events())
    if (e["event"] == "attach_frame") EXPECT_LE(e["app_frame"].get<int64_t>(), kept[3].get<int64_t>()) << "a frame was taken while frozen";

  // Space again: live; the next frame taken is newer than every kept one.
  xdotool("key --window " + wid_ + " space");
  ASSERT_FALSE(waitEvent([](const json& j) { return j["event"] == "history_frame" && j["state"] == "live"; }).is_null());
  const int64_t newest = kept[3];
  ASSERT_FALSE(waitEvent([&](const json& j) { return j["event"] == "attach_frame" && j["app_frame"] > newest; }).is_null())
      << "the stream did not come back after the freeze";

  // `,` while it runs freezes it too, one kept frame before the one shown; the probe's track is there at once.
  xdotool("key --window " + wid_ + " comma");
  EXPECT_FALSE(waitEvent([](const json& j) { return j["event"] == "attach_state" && j["state"] == "paused"; }).is_null());
  const json refrozen = waitEvent([](const json& j) { return j["event"] == "history_frame" && j["state"] == "frozen"; });
  ASSERT_FALSE(refrozen.is_null()) << "`,` on the running stream did not freeze it";
  const json again = waitEvent([](const json& j) { return j["event"] == "track"; });
  ASSERT_FALSE(again.is_null()) << "no track of the probe over the new kept frames";
  EXPECT_EQ(again["frames"], refrozen["frames"]);
  EXPECT_GT(refrozen["frames"][0].get<int64_t>(), newest) << "the kept frames are the newer ones";
  const json stepped = waitEvent([](const json& j) { return j["event"] == "history_frame" && j["index"] < 3; });
  ASSERT_FALSE(stepped.is_null()) << "`,` on the running stream did not step back a kept frame";
  EXPECT_EQ(stepped["app_frame"], refrozen["frames"][stepped["index"].get<size_t>()]);
  EXPECT_EQ(kill(app_, 0), 0) << "the application stopped";
}

}  // namespace gb
