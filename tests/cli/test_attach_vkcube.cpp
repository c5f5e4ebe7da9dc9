// gblens attach on vkcube (Debian's vulkan-tools: a real application nobody here wrote; forward, D16
// depth, its command buffers recorded once per swapchain image), under an Xvfb of the test's own,
// with vkcube's own validation (--validate) and synchronization validation on: any message fails.
// - builtin:vkcube streams application frame k: its colour equals what vkcube presented at frame k
//   as the test-only present-dump layer read it, and its depth equals the cube's depth computed
//   here from cube.c's geometry and matrices, pixel by pixel;
// - vkcube presents the same frame k with the gblens layer streaming and without it;
// - the window resized, the layer follows the new swapchain and depth images (library API).
#include "tests/support/test_paths.h"
#include <gtest/gtest.h>

#include <chrono>
#include <fstream>
#include <regex>
#include <thread>

#include "tests/cli/attach_util.h"
#include "tests/gui/gui_util.h"
#include "tests/support/capture_util.h"
#include "views/live/live.h"

namespace gb {
namespace {

class VkCube : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!gui::haveTool("Xvfb") || !gui::haveTool("vkcube"))
      GTEST_SKIP() << "needs Xvfb and vkcube (apt-get install xvfb vulkan-tools)";
    std::string error;
    ASSERT_TRUE(xvfb_.start(800, 600, error)) << error;
  }
  void TearDown() override { xvfb_.stop(); }
  std::string display() const { return "DISPLAY=" + xvfb_.display + " " + attach::kSyncValidation + " "; }
  gui::Xvfb xvfb_;
};

// vkcube's output is its validation messages (and the device it picked).
void expectClean(const RunResult& r) {
  EXPECT_EQ(r.output.find("VALIDATION"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("exited with status"), std::string::npos) << r.output;
}

TEST_F(VkCube, StreamsWhatItPresentsAndPresentsTheSame) {
  const std::string dir = freshDir("attach_vkcube");
  RunResult on = runShell(display() + attach::layerEnvironment("", dir + "/on.dump") + "'" + GBLENS_BINARY +
                          "' attach --layout builtin:vkcube --capture-frame 3 -o " + dir + "/live -- vkcube --c 40 --validate");
  ASSERT_EQ(on.exitCode, 0) << on.output;
  expectClean(on);
  // Exactly the application's frame 3: vkcube records its command buffers once, and the layer holds
  // back the submissions that would write frame 3's ring buffers again until gblens has read them.
  std::smatch m;
  ASSERT_TRUE(std::regex_search(on.output, m, std::regex("wrote application frame (\\d+)"))) << on.output;
  const uint32_t frame = uint32_t(std::stoul(m[1]));
  EXPECT_EQ(frame, 3u) << on.output;
  RunResult off = runShell(display() + attach::layerEnvironment("", dir + "/off.dump") +
                           "GBLENS_TEST_DUMP_FRAME=" + std::to_string(frame) + " DISABLE_GBLENS_LIVE=1 vkcube --c 40 --validate");
  ASSERT_EQ(off.exitCode, 0) << off.output;
  expectClean(off);
  attach::Dump withLayer, without;
  const std::string suffix = "." + std::to_string(frame);
  ASSERT_TRUE(attach::readDump(dir + "/on.dump" + suffix, withLayer)) << on.output;
  ASSERT_TRUE(attach::readDump(dir + "/off.dump" + suffix, without)) << off.output;
  EXPECT_TRUE(withLayer.texels == without.texels) << "vkcube presents another frame " << frame << " with the layer on";

  Capture live;
  std::string error;
  ASSERT_TRUE(loadCapture(dir + "/live", live, error)) << error;
  const CpuImage& color = live.frame.images[0].image;
  const CpuImage& depth = live.frame.images[1].image;
  ASSERT_EQ(color.width, withLayer.width);
  ASSERT_EQ(color.height, withLayer.height);
  ASSERT_EQ(withLayer.format, 44);  // VK_FORMAT_B8G8R8A8_UNORM: streamed as rgba8_unorm, R and B swapped back
  size_t colourDiffers = 0;
  for (size_t i = 0; i < size_t(color.width) * color.height; ++i) {
    const uint8_t* p = &withLayer.texels[4 * i];
    const uint8_t* s = &color.data[4 * i];
    colourDiffers += s[0] != p[2] || s[1] != p[1] || s[2] != p[0] || s[3] != p[3];
  }
  EXPECT_EQ(colourDiffers, 0u);

  // Depth: every pixel of the 500x500 image away from the cube's edges against the ray cast here.
  size_t checked = 0, hits = 0, wrong = 0;
  double worst = 0.0;
  for (uint32_t y = 0; y < depth.height; y += 3)
    for (uint32_t x = 0; x < depth.width; x += 3) {
      bool edge = false;
      const double want = attach::vkcubeDepth(frame, depth.width, depth.height, x, y, edge);
      if (edge) continue;
      const double got = live.frame.images[1].value(x, y, 0);
      ++checked;
      hits += want < 1.0;
      worst = std::max(worst, std::abs(got - want));
      wrong += std::abs(got - want) > 1.0 / 65535.0;  // D16: half a step of rounding, and interpolation
    }
  EXPECT_GT(hits, 2000u);
  EXPECT_GT(checked - hits, 2000u);
  EXPECT_EQ(wrong, 0u) << "of " << checked << " pixels; worst " << worst * 65535.0 << " D16 steps";
  std::printf("vkcube depth: %zu pixels (%zu on the cube), worst %.2f D16 steps from the ray cast\n", checked, hits,
              worst * 65535.0);
}

// --capture-frames on an application that records its command buffers once: every submission of
// the range waits until gblens has read the frame before it, so each frame k of the sequence is the
// frame vkcube presented as its frame k (the present-dump layer's file k), and the three differ.
TEST_F(VkCube, CaptureFramesAreTheFramesItPresents) {
  const std::string dir = freshDir("attach_vkcube_sequence");
  RunResult r = runShell(display() + attach::layerEnvironment("", dir + "/on.dump") + "'" + GBLENS_BINARY +
                         "' attach --layout builtin:vkcube --capture-frames 3..5 -o " + dir + "/seq -- vkcube --c 12 --validate");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  expectClean(r);
  EXPECT_NE(r.output.find("wrote application frames 3..5 (3 frames"), std::string::npos) << r.output;
  std::vector<uint8_t> previous;
  for (int k = 3; k <= 5; ++k) {
    SCOPED_TRACE("frame " + std::to_string(k));
    Capture c;
    std::string error;
    ASSERT_TRUE(loadCapture(dir + "/seq@" + std::to_string(k), c, error)) << error;
    attach::Dump presented;
    ASSERT_TRUE(attach::readDump(dir + "/on.dump." + std::to_string(k), presented)) << r.output;
    const CpuImage& color = c.frame.images[0].image;
    ASSERT_EQ(size_t(color.width) * color.height * 4, presented.texels.size());
    size_t differs = 0;
    for (size_t i = 0; i < size_t(color.width) * color.height; ++i) {  // B8G8R8A8 presented, rgba8 streamed
      const uint8_t* p = &presented.texels[4 * i];
      const uint8_t* s = &color.data[4 * i];
      differs += s[0] != p[2] || s[1] != p[1] || s[2] != p[0] || s[3] != p[3];
    }
    EXPECT_EQ(differs, 0u);
    EXPECT_NE(color.data, previous);  // the cube turns every frame
    previous = color.data;
  }
}

// Its command buffers are recorded once and submitted again, so each of its frames copies; paced, the
// frames not asked for are not sent (attach_util.h expectPacedStream, test_attach_pacing.cpp). Most
// frames sent are written again while read in place (vkcube's recordings share one ring slot): each
// such one asks for the next itself.
TEST_F(VkCube, APacedStreamSendsOnlyTheFramesAskedForEachEndingAfterItsAsk) {
  const std::string dir = freshDir("attach_vkcube_paced");
  LiveOptions o;
  o.layout = "builtin:vkcube";
  o.argv = {"vkcube", "--c", "100000", "--validate"};
  o.environment = {"DISPLAY=" + xvfb_.display, attach::kSyncValidation};
  o.log = dir + "/vkcube.log";
  attach::expectPacedStream(o, 3, false, true);
  EXPECT_EQ(readText(o.log).find("VALIDATION"), std::string::npos) << readText(o.log);
}

TEST_F(VkCube, FollowsAResizedWindow) {
  const std::string dir = freshDir("attach_vkcube_resize");
  std::ofstream(dir + "/layout.json") << R"({"format": "gblens-layout", "version": 1, "targets": [
    {"name": "color", "format": "rgba8_unorm", "source": {"live": {"pass": 0, "color": 0}},
     "quantities": [{"quantity": "display", "channels": [0, 1, 2], "encoding": "srgb"}]},
    {"name": "depth", "format": "d16", "source": {"live": {"pass": 0, "depth": true}},
     "quantities": [{"quantity": "depth", "channels": [0], "encoding": "eye"}]}]})";
  LiveOptions o;
  o.layout = dir + "/layout.json";
  o.argv = {"vkcube", "--validate"};
  o.every = 4;
  o.environment = {"DISPLAY=" + xvfb_.display, attach::kSyncValidation};
  o.log = dir + "/vkcube.log";
  LiveSession s;
  std::string error;
  ASSERT_TRUE(s.start(o, error)) << error;
  FrameSnapshot f;
  ASSERT_TRUE(s.wait(f, 30.0)) << (s.takeReports().empty() ? "" : s.takeReports()[0]);
  EXPECT_EQ(f.images[0].image.width, 500u);
  // No window manager: xdotool resizes vkcube's window (the root's only child, it has no name);
  // vkcube makes a new swapchain and depth image and records its command buffers again.
  const std::string x = "DISPLAY=" + xvfb_.display + " ";
  const std::string window = gui::run(x + "xwininfo -root -children | awk '/^ +0x/ {print $1; exit}'");
  ASSERT_FALSE(window.empty());
  gui::run(x + "xdotool windowsize " + window.substr(0, window.find('\n')) + " 320 240");
  bool resized = false;
  for (auto start = std::chrono::steady_clock::now(); !resized && std::chrono::steady_clock::now() - start < std::chrono::seconds(30);)
    if (s.wait(f, 1.0)) resized = f.images[0].image.width == 320 && f.images[0].image.height == 240 && f.images[1].present();
  EXPECT_TRUE(resized);
  for (const std::string& r : s.takeReports()) ADD_FAILURE() << r;
  s.stop();
  EXPECT_EQ(readText(dir + "/vkcube.log").find("VALIDATION"), std::string::npos) << readText(dir + "/vkcube.log");
}

}  // namespace
}  // namespace gb
