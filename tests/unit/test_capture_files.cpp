// Capture files without a GPU: atomic writes, interrupted captures refused, a capture directory
// never overwriting anything else.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "tests/support/capture_util.h"
#include "views/capture/capture.h"

namespace gb {

namespace fs = std::filesystem;

TEST(Capture, WritesAreAtomicAndAnInterruptedCaptureIsNeverAccepted) {
  std::string root = freshDir("atomic");
  std::string dir = root + "/cap", error;
  FrameSnapshot f = syntheticFrame(8, 6);
  CaptureMeta meta;
  ASSERT_TRUE(writeCapture(dir, f, meta, error)) << error;
  Capture c;
  ASSERT_TRUE(loadCapture(dir, c, error)) << error;

  // A failure halfway (a region cannot be captured; hdr comes after four written EXRs) leaves
  // the old capture untouched and no temporary directory behind.
  FrameSnapshot bad = f;
  bad.target(Target::Hdr).x0 = 1;
  EXPECT_FALSE(writeCapture(dir, bad, meta, error));
  EXPECT_NE(error.find("region"), std::string::npos) << error;
  ASSERT_TRUE(loadCapture(dir, c, error)) << error;
  EXPECT_EQ(std::distance(fs::directory_iterator(root), fs::directory_iterator{}), 1)
      << "a temporary directory was left beside the capture";

  // What an interruption before the rename leaves (everything but the manifest) is refused.
  std::string partial = root + "/partial";
  fs::copy(dir, partial);
  fs::remove(partial + "/manifest.json");
  CaptureProblem problem;
  EXPECT_FALSE(loadCapture(partial, c, error, &problem));
  EXPECT_EQ(problem, CaptureProblem::Missing);
  EXPECT_NE(error.find("no manifest.json"), std::string::npos) << error;

  // A capture replaces a capture; a directory holding something else is never overwritten.
  f.options.time = 7.0;
  ASSERT_TRUE(writeCapture(dir, f, meta, error)) << error;
  ASSERT_TRUE(loadCapture(dir, c, error)) << error;
  EXPECT_EQ(c.frame.options.time, 7.0);
  std::string other = root + "/other";
  fs::create_directories(other);
  std::ofstream(other + "/notes.txt") << "mine";
  EXPECT_FALSE(writeCapture(other, f, meta, error));
  EXPECT_NE(error.find("not overwritten"), std::string::npos) << error;
  EXPECT_EQ(readText(other + "/notes.txt"), "mine");
}

}  // namespace gb
