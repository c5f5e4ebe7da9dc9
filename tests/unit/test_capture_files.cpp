// Capture files without a GPU: atomic writes, interrupted captures refused, a capture directory
// never overwriting anything else.
#include <gtest/gtest.h>

#include <cmath>
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

// The writer runs the readers' manifest check before the rename (issue 29): a frame whose values
// JSON cannot hold (NaN is written as null) or whose layout would merge EXR channels is not written,
// and the old capture stays; the same frame made valid again is written and reads back.
TEST(Capture, NothingIsWrittenThatTheReadersWouldRefuse) {
  const std::string root = freshDir("write-check");
  const std::string dir = root + "/cap";
  std::string error;
  CaptureMeta meta;
  FrameSnapshot f = syntheticFrame(8, 6);
  ASSERT_TRUE(writeCapture(dir, f, meta, error)) << error;
  FrameSnapshot bad = f;
  bad.camera.eyeFromWorld[3][0] = std::nan("");
  EXPECT_FALSE(writeCapture(dir, bad, meta, error));
  EXPECT_NE(error.find("not written, it would not read back"), std::string::npos) << error;
  EXPECT_NE(error.find("manifest.json: camera.eyeFromWorld[12]"), std::string::npos) << error;
  bad = f;
  bad.sun.toSun = glm::dvec3(INFINITY, 0.0, 0.0);
  EXPECT_FALSE(writeCapture(dir, bad, meta, error));
  EXPECT_NE(error.find("sun.to_sun"), std::string::npos) << error;
  // Two channels of one name: OpenEXR would hold one of them.
  bad = f;
  Layout layout = bad.layout;
  const size_t hdr = size_t(bad.indexOf(Target::Hdr));
  layout.targets[hdr].channels[1] = layout.targets[hdr].channels[0];
  bad.setLayout(layout);
  bad.images = f.images;
  bad.absences = f.absences;
  bad.images[hdr].image.channels[1] = bad.images[hdr].image.channels[0];
  EXPECT_FALSE(writeCapture(dir, bad, meta, error));
  EXPECT_NE(error.find("named twice"), std::string::npos) << error;
  // Each refusal left the first capture as it was, and nothing beside it.
  Capture c;
  ASSERT_TRUE(loadCapture(dir, c, error)) << error;
  EXPECT_EQ(c.frame.camera.eyeFromWorld, f.camera.eyeFromWorld);
  EXPECT_EQ(std::distance(fs::directory_iterator(root), fs::directory_iterator{}), 1);
}

}  // namespace gb
