// gblens's verdicts on a renderer nobody here wrote: tests/subjects/gbuffer_zoo's seven G-buffer designs
// (world-space positions with TBN normals that are not renormalised, a forward renderer, a lighting
// pass with its own depth, a stencil that is not stored, linear depth in a float channel, view-space
// octahedral normals with reversed depth, a Y-down left-handed world with only clip_from_world). From
// its RenderDoc captures (`import --suggest-layout`) and attached live (`attach --suggest`), every
// quantity its hand-written truth file lists is drafted as it says or as unknown, never wrong, and
// the camera is found where the truth says; `check` is clean on each correct frame.
#include "tests/support/test_paths.h"
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "tests/cli/zoo_truth.h"
#include "tests/support/capture_util.h"

namespace gb {
namespace {

using json = nlohmann::json;

const std::string kCaptures = GBLENS_BUILD_DIR + "/zoo";

class ZooSuggest : public testing::TestWithParam<const char*> {};

// import --suggest-layout on the mode's capture: each quantity as the truth says (or unknown), the
// camera at the truth's offsets with its conventions; imported with the draft, `check` is clean.
TEST_P(ZooSuggest, TheDraftIsTheTruthAndItsFrameChecksClean) {
  const std::string mode = GetParam(), dir = freshDir("zoo_suggest_" + mode);
  const json truth = zoo::readJson(zoo::truthPath(mode));
  ASSERT_TRUE(truth.is_object()) << zoo::truthPath(mode);
  ASSERT_TRUE(std::filesystem::exists(kCaptures + "/" + mode + ".rdc")) << "the zoo_captures fixture did not run";
  RunResult r = runGblens("import '" + kCaptures + "/" + mode + ".rdc' --suggest-layout -o '" + dir + "/draft.json'");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const json draft = zoo::readJson(dir + "/draft.json");
  const zoo::Verdict v = zoo::compare(truth, draft, zoo::importTargets(draft));
  EXPECT_TRUE(v.wrong.empty()) << v.text() << "\n" << r.output;
  EXPECT_GT(v.right, 3) << v.text();
  if (!truth["gbuffer_pass"].is_null() || draft.contains("camera")) {
    EXPECT_EQ(zoo::compareCamera(truth, draft), "") << r.output;
  }
  RunResult imported = runGblens("import '" + kCaptures + "/" + mode + ".rdc' --layout '" + dir + "/draft.json' -o '" + dir + "/frame'");
  ASSERT_EQ(imported.exitCode, 0) << imported.output;
  RunResult check = runGblens("check '" + dir + "/frame'");
  EXPECT_EQ(check.exitCode, 0) << check.output;
}

INSTANTIATE_TEST_SUITE_P(Modes, ZooSuggest, testing::ValuesIn(zoo::kModes));

class LiveZoo : public testing::TestWithParam<const char*> {};

// attach --suggest on the running application: the same verdicts from the live attachments, the
// buffers its G-buffer pass binds and one streamed frame; streamed under the draft, a frame checks clean.
TEST_P(LiveZoo, TheLiveDraftIsTheTruthAndItsFrameChecksClean) {
  const std::string mode = GetParam(), dir = freshDir("zoo_live_" + mode);
  const json truth = zoo::readJson(zoo::truthPath(mode));
  const std::string app = std::string("'") + ZOO_BINARY + "' --mode " + mode;
  RunResult r = runShell("cd '" + dir + "' && DISPLAY= WAYLAND_DISPLAY= GBLENS_VALIDATE=1 '" + GBLENS_BINARY +
                         "' attach --suggest -o draft.json -- " + app + " --frames 12");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const json draft = zoo::readJson(dir + "/draft.json");
  const zoo::Verdict v = zoo::compare(truth, draft, zoo::liveTargets(draft));
  EXPECT_TRUE(v.wrong.empty()) << v.text() << "\n" << r.output;
  EXPECT_GT(v.right, 3) << v.text();
  if (!truth["gbuffer_pass"].is_null() || draft.contains("camera")) {
    EXPECT_EQ(zoo::compareCamera(truth, draft), "") << r.output;
    ASSERT_TRUE(draft["camera"].contains("live")) << draft["camera"].dump();  // read each frame, from the app's binding
  }
  RunResult streamed = runShell("GBLENS_VALIDATE=1 '" + std::string(GBLENS_BINARY) + "' attach --layout '" + dir +
                                "/draft.json' --capture-frame 2 -o '" + dir + "/frame' -- " + app + " --frames 5");
  ASSERT_EQ(streamed.exitCode, 0) << streamed.output;
  RunResult check = runGblens("check '" + dir + "/frame'");
  EXPECT_EQ(check.exitCode, 0) << check.output;
}

INSTANTIATE_TEST_SUITE_P(Modes, LiveZoo, testing::ValuesIn(zoo::kModes));

}  // namespace
}  // namespace gb
