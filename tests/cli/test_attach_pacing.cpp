// A paced stream (the viewer's: LiveOptions::paced, `attach --pace on`): the layer copies a frame
// only when gblens has asked for it, so an application runs on at its own cost while the viewer is
// busy or paused, and the frame that comes after the ask is one the application ended after it.
// tests/subjects/tiler_deferred records its command buffers once a frame (copies only in frames
// asked for); vkcube (test_attach_vkcube.cpp) records them once and submits them again.
#include "tests/support/test_paths.h"
#include <gtest/gtest.h>

#include "tests/cli/attach_util.h"
#include "tests/cli/tiler_subject.h"
#include "tests/support/capture_util.h"

namespace gb {
namespace {

TEST(AttachPacing, APacedStreamCopiesOnlyTheFramesAskedForEachEndingAfterItsAsk) {
  const std::string dir = freshDir("attach_paced_tiler");
  LiveOptions o;
  o.layout = tiler_test::tilerDir() + "/layout_subpass.json";
  o.argv = {tiler_test::tiler(), "--mode", "subpass", "--frames", "1500"};
  o.environment = {"GBLENS_VALIDATE=1"};
  o.log = dir + "/app.log";
  attach::expectPacedStream(o, 4, true);
}

TEST(AttachPacing, PaceIsTheViewersAndFramesFlagAndRefusedWithACapture) {
  const RunResult r = runShell("'" + std::string(GBLENS_BINARY) + "' attach --layout '" + tiler_test::tilerDir() +
                               "/layout_subpass.json' --pace on --capture-frame 2 -o '" + freshDir("attach_pace_refused") +
                               "/cap' -- '" + tiler_test::tiler() + "'");
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find("--pace: paces the viewer's stream or --frames; --capture-frame takes the frames it names"),
            std::string::npos) << r.output;
}

}  // namespace
}  // namespace gb
