// From an unfamiliar RenderDoc capture to a layout (issue 25): `import --list` shows the buffers each
// pass binds, `import --suggest-layout` drafts the targets and finds the camera, and the draft
// imports as it is. Checked on a capture of gblens's own frame against what gblens knows
// independently: the binding and offsets its shaders declare (shaders/shared.h), the camera of a
// `gblens capture` of the same frame, and the stored positions. And the docs' own example: a
// RenderDoc capture of `gblens render` imported with builtin:gblens compares clean against `gblens
// capture` of the same frame (gblens's 1x1 stand-ins are absent, not targets).
#include "tests/support/test_paths.h"
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstddef>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "renderer/core/decode.h"
#include "renderer/core/layout_json.h"
#include "shaders/shared.h"
#include "tests/support/capture_util.h"
#include "views/capture/capture.h"

namespace gb {
namespace {

namespace fs = std::filesystem;

std::string renderDocCapture(const std::string& dir, const std::string& args) {
  RunResult r = runShell("timeout -k 5 120 renderdoccmd capture -w -c '" + dir + "/frame' '" + GBLENS_BINARY + "' " + args);
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().extension() == ".rdc") return e.path().string();
  ADD_FAILURE() << "renderdoccmd wrote no .rdc:\n" << r.output;
  return "";
}

void requireRenderDoc() {
  ASSERT_EQ(access("/usr/bin/renderdoccmd", X_OK), 0) << "renderdoccmd is not installed (make deps)";
}

Capture load(const std::string& dir) {
  Capture c;
  std::string error;
  EXPECT_TRUE(loadCapture(dir, c, error)) << error;
  return c;
}

const char* kFrame = "--size 96x54 --lights 8 --shadow-map-size 128 --position rgba32f";

TEST(RenderDoc, ListShowsBuffersAndSuggestFindsTheCameraOfGblensOwnFrame) {
  requireRenderDoc();
  const std::string dir = freshDir("suggest-gblens");
  const std::string rdc = renderDocCapture(dir, std::string("capture ") + kFrame + " -o '" + dir + "/under'");
  ASSERT_FALSE(rdc.empty());
  RunResult plainRun = runGblens(std::string("capture ") + kFrame + " -o '" + dir + "/plain'");
  ASSERT_EQ(plainRun.exitCode, 0) << plainRun.output;
  const Capture plain = load(dir + "/plain");

  // --list: the uniform buffer "frame" where the shaders declare it, as big as FrameData, under the
  // G-buffer pass; every buffer with its size.
  RunResult list = runGblens("import '" + rdc + "' --list");
  ASSERT_EQ(list.exitCode, 0) << list.output;
  const size_t gbuffer = list.output.find("\n    gbuffer ");
  ASSERT_NE(gbuffer, std::string::npos) << list.output;
  const size_t frameLine = list.output.find("uniform frame ", gbuffer);
  ASSERT_NE(frameLine, std::string::npos) << list.output;
  const std::string line = list.output.substr(frameLine, list.output.find('\n', frameLine) - frameLine);
  EXPECT_NE(line.find(" " + std::to_string(sizeof(gpu::FrameData)) + " bytes"), std::string::npos) << line;
  EXPECT_NE(line.find("set 0 binding " + std::to_string(gpu::kBindingFrame) + ", bytes 0.."), std::string::npos) << line;
  EXPECT_NE(line.find("vertex"), std::string::npos) << line;
  EXPECT_NE(line.find("fragment"), std::string::npos) << line;
  EXPECT_NE(list.output.find("\nbuffers   "), std::string::npos) << list.output;

  // --suggest-layout: the G-buffer pass's targets and the camera at FrameData's offsets, confirmed
  // by the stored (world-space) positions.
  const std::string draftPath = dir + "/draft.json";
  RunResult suggest = runGblens("import '" + rdc + "' --suggest-layout -o '" + draftPath + "'");
  ASSERT_EQ(suggest.exitCode, 0) << suggest.output;
  const nlohmann::json draft = nlohmann::json::parse(std::ifstream(draftPath));
  Layout layout;
  std::string error;
  ASSERT_TRUE(parseLayout(draft, draftPath, layout, error)) << error;
  for (const char* t : {"albedo_specular", "normal_shadow", "depth", "position", "depth_stencil"})
    EXPECT_GE(layout.findTarget(t), 0) << t << " in " << draft.dump(1);
  const nlohmann::json& cam = draft["camera"];
  ASSERT_TRUE(cam.contains("renderdoc")) << cam.dump();
  EXPECT_EQ(cam["renderdoc"]["buffer"], "frame");
  EXPECT_EQ(cam["renderdoc"]["clip_from_view"]["offset"], offsetof(gpu::FrameData, clipFromEye));
  EXPECT_EQ(cam["renderdoc"]["world_from_view"]["offset"], offsetof(gpu::FrameData, worldFromEye)) << cam.dump();
  EXPECT_EQ(cam["convention"], "vulkan");
  EXPECT_EQ(cam["up"], "y");
  EXPECT_EQ(cam["projection"], "perspective");
  ASSERT_NE(layout.find(QuantityKind::Position), nullptr);
  EXPECT_EQ(layout.find(QuantityKind::Position)->space, Space::World);
  EXPECT_EQ(suggest.output.find("  .. "), std::string::npos) << "progress lines are for a terminal, not a pipe";

  // The draft imports as it is: the camera is the frame's (float matrices), positions rebuilt from
  // its depth are its stored ones within float rounding, and the import names where the camera came from.
  RunResult imported = runGblens("import '" + rdc + "' --layout '" + draftPath + "' -o '" + dir + "/imported'");
  ASSERT_EQ(imported.exitCode, 0) << imported.output;
  EXPECT_NE(imported.output.find("camera    buffer \"frame\" (#"), std::string::npos) << imported.output;
  const Capture got = load(dir + "/imported");
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) {
      EXPECT_EQ(got.frame.camera.clipFromEye[c][r], double(float(plain.frame.camera.clipFromEye[c][r])));
      EXPECT_NEAR(got.frame.camera.worldFromEye[c][r], plain.frame.camera.worldFromEye[c][r], 1e-5);
    }
  const Quantity* position = got.frame.layout.find(QuantityKind::Position);
  const Quantity* depth = surfaceDepth(got.frame.layout);
  ASSERT_TRUE(position && depth);
  size_t compared = 0;
  for (uint32_t y = 0; y < got.frame.camera.height; ++y)
    for (uint32_t x = 0; x < got.frame.camera.width; ++x) {
      std::optional<glm::dvec3> fromDepth = decodePosition(got.frame, *depth, x, y);
      if (!fromDepth) continue;
      const glm::dvec3 stored = *decodePosition(got.frame, *position, x, y);
      // Both are float32 results of the same eye position: a few ulps of the scene's extent (~20).
      EXPECT_NEAR(glm::length(*fromDepth - stored), 0.0, 2e-5 * std::max(1.0, glm::length(stored))) << x << "," << y;
      ++compared;
    }
  EXPECT_GT(compared, 1000u);

  // A camera buffer name the capture does not have: the error lists every buffer with its size and
  // where the draw binds it, so the right one can be picked.
  nlohmann::json wrong = draft;
  wrong["camera"]["renderdoc"]["buffer"] = "FrameConstants";
  std::ofstream(dir + "/wrong.json") << wrong.dump();
  RunResult refused = runGblens("import '" + rdc + "' --layout '" + dir + "/wrong.json' -o '" + dir + "/wrong'");
  EXPECT_EQ(refused.exitCode, 2) << refused.output;
  EXPECT_NE(refused.output.find("no buffer named \"FrameConstants\" (buffers: "), std::string::npos) << refused.output;
  EXPECT_NE(refused.output.find(" " + std::to_string(sizeof(gpu::FrameData)) + " bytes (uniform at set 0 binding " +
                                std::to_string(gpu::kBindingFrame) + ", event "),
            std::string::npos)
      << refused.output;
  EXPECT_FALSE(fs::exists(dir + "/wrong"));
}

TEST(RenderDoc, TheDocsExampleImportsWithBuiltinGblensAndComparesClean) {
  requireRenderDoc();
  const std::string dir = freshDir("suggest-readme");
  const std::string rdc = renderDocCapture(dir, "render --size 160x90 --time 1 -o '" + dir + "/f.png'");
  ASSERT_FALSE(rdc.empty());
  RunResult imported = runGblens("import '" + rdc + "' --layout builtin:gblens -o '" + dir + "/imported'");
  ASSERT_EQ(imported.exitCode, 0) << imported.output;
  EXPECT_NE(imported.output.find("absent: its texture is a 1x1 stand-in"), std::string::npos) << imported.output;
  RunResult plain = runGblens("capture --size 160x90 --time 1 -o '" + dir + "/plain'");
  ASSERT_EQ(plain.exitCode, 0) << plain.output;
  RunResult compare = runGblens("compare '" + dir + "/plain' '" + dir + "/imported'");
  EXPECT_EQ(compare.exitCode, 0) << compare.output;
}

}  // namespace
}  // namespace gb
