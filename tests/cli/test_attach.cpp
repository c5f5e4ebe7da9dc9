// gblens attach with gblens's own renderer as the application (`gblens render`, validation and
// synchronization validation on inside it, so the layer's copies and barriers are checked):
// - with builtin:gblens the streamed frame equals `gblens capture` of the same frame, bit for bit in
//   every target the frame's render passes write (and the camera read from its uniform buffer);
// - the receiver killed mid-stream: the application runs to its end with exit 0;
// - no receiver: the layer stays idle and the application's frame is as without it;
// - a layout naming an image the application never makes, or another format, is reported once and
//   the target left out (never decoded as something else); nothing matched: exit 2 with why.
#include "tests/support/test_paths.h"
#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <regex>
#include <thread>

#include "tests/cli/attach_util.h"
#include "tests/gui/gui_util.h"
#include "tests/support/capture_util.h"

namespace gb {
namespace {

namespace fs = std::filesystem;

const std::string kFrame = "--size 96x54 --lights 8 --shadow-map-size 128 --time 1.5";

std::string app(const std::string& args) { return std::string("'") + GBLENS_BINARY + "' " + args; }

size_t count(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

TEST(Attach, GblensStreamEqualsItsCapture) {
  const std::string dir = freshDir("attach_gblens");
  // The first streamed frame is the application's first: the only one that renders the shadow map
  // (a static scene reuses it), so every target gblens capture reads back is in it.
  RunResult r = runGblens("attach --layout builtin:gblens --capture-frame 0 -o " + dir + "/live -- " +
                          app("render " + kFrame + " --frames 3 --validate -o " + dir + "/frame.png"));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_EQ(r.output.find("exited with status"), std::string::npos) << r.output;  // validation clean
  RunResult c = runGblens("capture " + kFrame + " --coverage off -o " + dir + "/capture");
  ASSERT_EQ(c.exitCode, 0) << c.output;
  Capture live, ref;
  std::string error;
  ASSERT_TRUE(loadCapture(dir + "/live", live, error)) << error;
  ASSERT_TRUE(loadCapture(dir + "/capture", ref, error)) << error;
  // Every target the capture has that a render pass writes (coverage is off: its counters are not made).
  for (const char* t : {"albedo_specular", "normal_shadow", "depth", "depth_stencil", "shadow_map", "hdr", "final"}) {
    ASSERT_GE(live.frame.indexOf(t), 0);
    EXPECT_TRUE(live.frame.images[size_t(live.frame.indexOf(t))].present()) << t << "\n" << r.output;
  }
  const std::vector<std::string> differ = attach::texelDifferences(live, ref);
  EXPECT_TRUE(differ.empty()) << differ.front();
  // The camera read from the uniform buffer "frame" (float matrices) is the renderer's (double).
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 4; ++k) {
      EXPECT_NEAR(live.frame.camera.eyeFromWorld[i][k], ref.frame.camera.eyeFromWorld[i][k], 1e-5);
      EXPECT_NEAR(live.frame.camera.clipFromEye[i][k], ref.frame.camera.clipFromEye[i][k], 1e-5 * std::abs(ref.frame.camera.clipFromEye[i][k]) + 1e-6);
    }
}

// A G-buffer written by compute (the visibility G-buffer: gbuffer_resolve writes albedo, normals and
// eye depth into storage images no render pass holds) is streamed from after the dispatches that
// write it: every target equals `gblens capture` of the same frame bit for bit (validation and
// synchronization validation in the application: the copies' layouts and barriers are checked).
TEST(Attach, AGBufferWrittenByComputeStreamsAsItsCapture) {
  const std::string dir = freshDir("attach_visibility");
  const std::string frame = kFrame + " --gbuffer visibility";
  RunResult r = runGblens("attach --layout builtin:gblens --capture-frame 0 -o " + dir + "/live -- " +
                          app("render " + frame + " --frames 2 --validate -o " + dir + "/frame.png"));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_EQ(r.output.find("exited with status"), std::string::npos) << r.output;  // validation clean
  for (const char* t : {"albedo_specular", "normal_shadow", "depth"})
    EXPECT_NE(r.output.find(std::string(t) + " ", 0), std::string::npos) << r.output;
  EXPECT_EQ(count(r.output, "compute dispatch \"gbuffer_resolve\""), 3u) << r.output;  // the three storage targets
  RunResult c = runGblens("capture " + frame + " --coverage off -o " + dir + "/capture");
  ASSERT_EQ(c.exitCode, 0) << c.output;
  Capture live, ref;
  std::string error;
  ASSERT_TRUE(loadCapture(dir + "/live", live, error)) << error;
  ASSERT_TRUE(loadCapture(dir + "/capture", ref, error)) << error;
  for (const char* t : {"albedo_specular", "normal_shadow", "depth", "depth_stencil", "visibility", "hdr", "final"}) {
    ASSERT_GE(live.frame.indexOf(t), 0) << t;
    EXPECT_TRUE(live.frame.images[size_t(live.frame.indexOf(t))].present()) << t << "\n" << r.output;
  }
  const std::vector<std::string> differ = attach::texelDifferences(live, ref);
  EXPECT_TRUE(differ.empty()) << differ.front();
}

// The layer's storage copies, counted in --stats: the visibility G-buffer's three storage targets in
// every streamed frame; a compute clear of the raster
// G-buffer's targets none (the barrier to COLOR_ATTACHMENT keeps the copy pending and the G-buffer
// pass, which writes them, drops it: copying at the barrier would make 3 a frame).
TEST(Attach, StorageImagesAreCopiedOnceAfterTheirLastWriterAndNotBeforeAPassWritingThem) {
  auto storageCopies = [](const std::string& options, uint64_t& streamed) -> uint64_t {
    RunResult r = runGblens("attach --layout builtin:gblens --frames 3 --stats -- " +
                            app("render " + kFrame + " --frames 8 " + options + " -o " + freshDir("attach_storage") + "/f.png"));
    EXPECT_EQ(r.exitCode, 0) << r.output;
    const size_t json = r.output.find("{\n");
    if (json == std::string::npos) return ~0ull;
    nlohmann::json stats = nlohmann::json::parse(r.output.substr(json, r.output.rfind('}') - json + 1), nullptr, false);
    if (!stats.is_object()) return ~0ull;
    streamed = stats["layer"]["streamed"].get<uint64_t>();
    return stats["layer"]["storage_copies"].get<uint64_t>();
  };
  uint64_t streamed = 0;
  const uint64_t visibility = storageCopies("--gbuffer visibility", streamed);
  EXPECT_GE(streamed, 3u);
  // (frames the layer began to copy but did not stream, at the connect, count too)
  EXPECT_GE(visibility, 3 * streamed);
  EXPECT_EQ(storageCopies("--gbuffer raster --method clustered --gbuffer-clear compute", streamed), 0u);
  EXPECT_GE(streamed, 3u);
}

TEST(Attach, EveryNthFrameAndStats) {
  const std::string dir = freshDir("attach_every");
  RunResult r = runGblens("attach --layout builtin:gblens --capture-frame 4 --stats -o " + dir + "/live -- " +
                          app("render " + kFrame + " --frames 6 -o " + dir + "/frame.png"));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  // --capture-frame N is the application's frame N (0: its first), the only one streamed.
  EXPECT_NE(r.output.find("wrote application frame 4 (streamed frame 1)"), std::string::npos) << r.output;
  const size_t json = r.output.find("{\n");
  ASSERT_NE(json, std::string::npos) << r.output;
  nlohmann::json stats = nlohmann::json::parse(r.output.substr(json, r.output.rfind('}') - json + 1), nullptr, false);
  ASSERT_TRUE(stats.is_object()) << r.output;
  EXPECT_EQ(stats["received"], 1);
  EXPECT_GT(stats["layer"]["ring_bytes"].get<double>(), 0.0);
  EXPECT_GT(stats["layer"]["frame_ms"].get<double>(), 0.0);
}

// GBLENS_LAYER_TIMESTAMPS=1 (docs/attach.md "Cost"): the layer times its copies on the GPU, each copy
// command under the image it copies (gblens names its images by target; depth and stencil apart);
// without it there are no timings. The times themselves are the device's (make bench reports them).
TEST(Attach, TimestampsTimeEveryCopyOfTheStreamedTargetsOnlyWhenAsked) {
  auto copyTiming = [](bool on) {
    if (on) setenv("GBLENS_LAYER_TIMESTAMPS", "1", 1);
    RunResult r = runGblens("attach --layout builtin:gblens --frames 16 --stats -- " +
                            app("render " + kFrame + " --frames 40 -o " + freshDir("attach_timestamps") + "/f.png"));
    unsetenv("GBLENS_LAYER_TIMESTAMPS");
    EXPECT_EQ(r.exitCode, 0) << r.output;
    const size_t json = r.output.find("{\n");
    if (json == std::string::npos) return nlohmann::json();
    const nlohmann::json stats = nlohmann::json::parse(r.output.substr(json, r.output.rfind('}') - json + 1), nullptr, false);
    return stats.is_object() ? stats["layer"]["copy_gpu"] : nlohmann::json();
  };
  const nlohmann::json timing = copyTiming(true);
  ASSERT_TRUE(timing.is_object()) << timing.dump();
  EXPECT_GE(timing["blocks"].get<int>(), 4);
  for (const char* copy : {"albedo_specular", "normal_shadow", "depth_stencil depth", "depth_stencil stencil", "final"}) {
    ASSERT_TRUE(timing["by_copy_ms"].contains(copy)) << copy << ": " << timing.dump();
    EXPECT_GT(timing["by_copy_ms"][copy].get<double>(), 0.0) << copy;
  }
  EXPECT_GT(timing["copies_ms"].get<double>(), 0.0);
  EXPECT_TRUE(copyTiming(false).is_null());
}

TEST(Attach, KilledReceiverLeavesTheApplicationRunning) {
  const std::string dir = freshDir("attach_kill");
  const std::string status = dir + "/status";
  // The receiver streams every frame; the application (a shell that records its exit status)
  // renders 30 frames with validation on.
  const pid_t receiver = gui::spawn(
      {GBLENS_BINARY, "attach", "--layout", "builtin:gblens", "--frames", "100000", "--", "sh", "-c",
       app("render " + kFrame + " --frames 30 --validate -o " + dir + "/frame.png") + "; echo $? > '" + status + "'"},
      {"GBLENS_LAYER_LOG=1"}, dir + "/attach.log");
  const auto start = std::chrono::steady_clock::now();
  while (count(readText(dir + "/attach.log"), "): sent") < 3 && std::chrono::steady_clock::now() - start < std::chrono::seconds(60))
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  ASSERT_GE(count(readText(dir + "/attach.log"), "): sent"), 3u) << readText(dir + "/attach.log");
  kill(receiver, SIGKILL);  // mid-stream: the layer finds the socket closed and goes idle
  int exitCode = -2;
  gui::waitExit(receiver, 10.0, exitCode);
  for (int i = 0; i < 600 && !fs::exists(status); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(100));
  EXPECT_EQ(readText(status), "0\n") << readText(dir + "/attach.log");
  EXPECT_EQ(readText(dir + "/attach.log").find("validation message"), std::string::npos) << readText(dir + "/attach.log");
}

TEST(Attach, NoReceiverLeavesTheLayerIdle) {
  const std::string dir = freshDir("attach_idle");
  // The layer loaded (the loader says so) but nobody listens on the socket: the frame is as without it.
  RunResult idle = runShell(attach::layerEnvironment(dir + "/nobody") + "VK_LOADER_DEBUG=layer " +
                            app("capture " + kFrame + " --coverage off --validate -o " + dir + "/idle"));
  ASSERT_EQ(idle.exitCode, 0) << idle.output;
  EXPECT_NE(idle.output.find("Insert instance layer \"VK_LAYER_GBLENS_live\""), std::string::npos) << idle.output;
  RunResult plain = runGblens("capture " + kFrame + " --coverage off -o " + dir + "/plain");
  ASSERT_EQ(plain.exitCode, 0) << plain.output;
  Capture a, b;
  std::string error;
  ASSERT_TRUE(loadCapture(dir + "/idle", a, error)) << error;
  ASSERT_TRUE(loadCapture(dir + "/plain", b, error)) << error;
  const std::vector<std::string> differ = attach::texelDifferences(a, b);
  EXPECT_TRUE(differ.empty()) << differ.front();
}

TEST(Attach, MissingImageAndWrongFormatAreReportedOnce) {
  const std::string dir = freshDir("attach_reports");
  std::ofstream(dir + "/layout.json") << R"({"format": "gblens-layout", "version": 1, "targets": [
    {"name": "albedo", "format": "rgba8_srgb", "source": {"live": {"name": "albedo_specular"}},
     "quantities": [{"quantity": "albedo", "channels": [0, 1, 2]}]},
    {"name": "normals", "format": "rgba16f", "source": {"live": {"pass": "gbuffer", "color": 1}},
     "quantities": [{"quantity": "normal", "channels": [0, 1, 2]}]},
    {"name": "ghost", "format": "r8_unorm", "source": {"live": "no_such_image"},
     "quantities": [{"quantity": "scalar", "channels": [0]}]}]})";
  RunResult r = runGblens("attach --layout " + dir + "/layout.json --capture-frame 2 -o " + dir + "/live -- " +
                          app("render " + kFrame + " --frames 6 -o " + dir + "/frame.png"));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  // gblens's normals are rgba16_snorm by default: named, not decoded as half floats.
  EXPECT_EQ(count(r.output, "target \"normals\": colour attachment 1 of pass \"gbuffer\" is rgba16_snorm"), 1u) << r.output;
  EXPECT_EQ(count(r.output, "target \"ghost\": frame"), 1u) << r.output;
  EXPECT_EQ(count(r.output, "has no render pass or compute dispatch with the image named \"no_such_image\""), 1u) << r.output;
  Capture live;
  std::string error;
  ASSERT_TRUE(loadCapture(dir + "/live", live, error)) << error;
  EXPECT_TRUE(live.frame.images[0].present());
  EXPECT_FALSE(live.frame.images[1].present());
  EXPECT_FALSE(live.frame.images[2].present());
}

TEST(Attach, NothingMatchedExitsTwoWithWhy) {
  const std::string dir = freshDir("attach_nothing");
  std::ofstream(dir + "/layout.json") << R"({"format": "gblens-layout", "version": 1, "targets": [
    {"name": "ghost", "format": "r8_unorm", "source": {"live": "no_such_image"},
     "quantities": [{"quantity": "scalar", "channels": [0]}]}]})";
  RunResult r = runGblens("attach --layout " + dir + "/layout.json --capture-frame 0 -o " + dir + "/live -- " +
                          app("render " + kFrame + " --frames 4 -o " + dir + "/frame.png"));
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find("no_such_image"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("the application ended after 0 streamed frame(s), before its frame 0"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir + "/live"));
}

TEST(Attach, UsageMistakes) {
  const std::string dir = freshDir("attach_usage");
  // The viewer opens on the first frame: an application that makes none ends it before any window.
  RunResult viewer = runGblens("attach --layout builtin:gblens -- true");
  EXPECT_EQ(viewer.exitCode, 2);
  EXPECT_NE(viewer.output.find("the application ended without creating a Vulkan device under the layer"), std::string::npos)
      << viewer.output;
  RunResult noLayout = runGblens("attach -- true");
  EXPECT_EQ(noLayout.exitCode, 2);
  EXPECT_NE(noLayout.output.find("--layout: required for the viewer"), std::string::npos) << noLayout.output;
  std::ofstream(dir + "/files.json") << R"({"format": "gblens-layout", "version": 1, "targets": [
    {"name": "a", "format": "rgba8_unorm", "source": {"file": "a.png"}, "quantities": [{"quantity": "albedo", "channels": [0, 1, 2]}]}]})";
  RunResult file = runGblens("attach --layout " + dir + "/files.json --capture-frame 1 -o " + dir + "/x -- true");
  EXPECT_EQ(file.exitCode, 2);
  EXPECT_NE(file.output.find("targets[0]: \"a\": source.file: gblens attach streams render-pass attachments"),
            std::string::npos) << file.output;
  RunResult noApp = runGblens("attach --layout builtin:gblens --capture-frame 1 -o " + dir + "/x -- /no/such/app");
  EXPECT_EQ(noApp.exitCode, 2);
  EXPECT_NE(noApp.output.find("/no/such/app: cannot start it"), std::string::npos) << noApp.output;
  // --suggest drafts the layout --capture-frame would need; an application without Vulkan leaves nothing to draft
  // from, and the draft's file is not written.
  RunResult both = runGblens("attach --suggest --capture-frame 1 -o " + dir + "/x -- true");
  EXPECT_EQ(both.exitCode, 2);
  EXPECT_NE(both.output.find("--suggest: drafts a layout; --capture-frame and --frames need --layout"), std::string::npos)
      << both.output;
  RunResult every = runGblens("attach --layout builtin:gblens --every 2 --capture-frame 4 -o " + dir + "/x -- true");
  EXPECT_EQ(every.exitCode, 2);
  EXPECT_NE(every.output.find("--every: --capture-frame names one frame of the application"), std::string::npos) << every.output;
  RunResult nothing = runGblens("attach --suggest -o " + dir + "/draft.json -- true");
  EXPECT_EQ(nothing.exitCode, 2);
  EXPECT_NE(nothing.output.find("the application ended without creating a Vulkan device under the layer"), std::string::npos)
      << nothing.output;
  EXPECT_FALSE(std::filesystem::exists(dir + "/draft.json"));
}

}  // namespace
}  // namespace gb
