// Sequences without a device (issue 38): sequence.json written and read back, every malformed manifest
// refused in one line naming the file and the field, SEQ@N resolved, frame patterns, the motion
// quantity's y and jitter fields and a camera's jitter and time; and the conventions' stored <->
// motion conversions against hand-computed vectors.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "renderer/core/layout_json.h"
#include "tests/support/capture_util.h"
#include "views/analysis/motion.h"
#include "views/capture/sequence.h"

namespace gb {
namespace {

using json = nlohmann::json;

std::string writeTwoFrames(const std::string& dir) {
  std::string error;
  const bool ok = writeSequence(dir, 2, [](size_t i, SequenceEntry& e, std::string&) {
    e.frame = syntheticFrame(8, 4);
    e.number = 10 + int64_t(i) * 5;
    e.time = 0.5 * double(i);
    if (i == 1) e.jitter = glm::dvec2(0.25, -0.125);
    return true;
  }, json{{"command_line", "test"}}, error);
  EXPECT_TRUE(ok) << error;
  return dir;
}

TEST(Sequence, WrittenFramesReadBackWithNumbersTimesAndJitter) {
  const std::string dir = writeTwoFrames(freshDir("seq-unit") + "/s");
  Sequence s;
  std::string error;
  ASSERT_TRUE(loadSequence(dir, s, error)) << error;
  ASSERT_EQ(s.frames.size(), 2u);
  EXPECT_EQ(s.frames[0].number, 10);
  EXPECT_EQ(s.frames[1].number, 15);
  EXPECT_EQ(s.frames[1].time.value_or(-1), 0.5);
  EXPECT_FALSE(s.frames[0].jitter.has_value());  // not said: null, never 0
  EXPECT_EQ(s.frames[1].jitter.value_or(glm::dvec2(9)), glm::dvec2(0.25, -0.125));
  EXPECT_EQ(s.manifest["command_line"], "test");
  std::string frameDir;
  ASSERT_TRUE(resolveSequenceFrame(dir + "@15", frameDir, error)) << error;
  EXPECT_EQ(frameDir, s.captureDir(1));
  EXPECT_FALSE(resolveSequenceFrame(dir + "@11", frameDir, error));
  EXPECT_NE(error.find("no frame 11 (frames 10..15)"), std::string::npos) << error;
  EXPECT_FALSE(resolveSequenceFrame(dir, frameDir, error));
  EXPECT_TRUE(error.empty());  // not of the SEQ@N form: a capture folder, loadCapture's business
}

TEST(Sequence, EveryMalformedManifestIsOneLineNamingTheField) {
  const std::string dir = writeTwoFrames(freshDir("seq-bad") + "/s");
  const json good = json::parse(readText(dir + "/sequence.json"));
  struct Case {
    std::string pointer;
    json value;
    std::string expected;
  };
  const std::vector<Case> cases = {
      {"/format", "gblens-capture", "format: expected \"gblens-sequence\""},
      {"/format_version", 7, "format_version: version 7 is newer than this gblens reads (1)"},
      {"/frames", json::array(), "frames: no frames"},
      {"/frames/1/frame", 10, "frames[1].frame: frame numbers must increase"},
      {"/frames/0/dir", "../elsewhere", "dir: expected a folder name inside the sequence"},
      {"/frames/0/dir", "frame_9999", "no folder frame_9999 in the sequence"},
      {"/frames/1/jitter", json::array({1}), "jitter: expected [x, y] in pixels"},
      {"/frames/0/time", "soon", "time: expected"},
  };
  for (const Case& c : cases) {
    json j = good;
    j[json::json_pointer(c.pointer)] = c.value;
    std::ofstream(dir + "/sequence.json") << j.dump();
    Sequence s;
    std::string error;
    EXPECT_FALSE(loadSequence(dir, s, error)) << c.pointer;
    EXPECT_NE(error.find(c.expected), std::string::npos) << c.pointer << ": got \"" << error << "\"";
    EXPECT_NE(error.find("sequence.json"), std::string::npos) << error;
    EXPECT_EQ(error.find('\n'), std::string::npos) << error;
  }
}

TEST(Sequence, AnExistingFolderThatIsNoSequenceIsNeverReplaced) {
  const std::string dir = freshDir("seq-clobber") + "/mine";
  std::filesystem::create_directories(dir);
  std::ofstream(dir + "/notes.txt") << "keep";
  std::string error;
  EXPECT_FALSE(writeSequence(dir, 1, [](size_t, SequenceEntry& e, std::string&) {
    e.frame = syntheticFrame(4, 4);
    return true;
  }, json::object(), error));
  EXPECT_TRUE(std::filesystem::exists(dir + "/notes.txt"));
  // A producer that fails leaves nothing at all.
  const std::string other = freshDir("seq-fail") + "/s";
  EXPECT_FALSE(writeSequence(other, 3, [](size_t i, SequenceEntry& e, std::string& why) {
    e.frame = syntheticFrame(4, 4);
    why = "frame 2 broke";
    return i < 2;
  }, json::object(), error));
  EXPECT_NE(error.find("frame 2 broke"), std::string::npos) << error;
  EXPECT_FALSE(std::filesystem::exists(other));
}

TEST(Sequence, FramePatternsAndRanges) {
  EXPECT_EQ(framePath("cycles_####.exr", 7), "cycles_0007.exr");
  EXPECT_EQ(framePath("app_frame#.rdc", 120), "app_frame120.rdc");
  EXPECT_EQ(framePath("a##_b###.exr", 12345), "a12345_b12345.exr");
  EXPECT_EQ(framePath("plain.exr", 3), "plain.exr");
  int64_t a = 0, b = 0;
  std::string error;
  EXPECT_TRUE(parseFrameRange("3..9", "--frames", a, b, error));
  EXPECT_EQ(a, 3);
  EXPECT_EQ(b, 9);
  EXPECT_TRUE(parseFrameRange("4", "--frames", a, b, error));
  EXPECT_EQ(a, 4);
  EXPECT_EQ(b, 4);
  for (const char* bad : {"9..3", "a..b", "", "1..", "..2"}) {
    EXPECT_FALSE(parseFrameRange(bad, "--frames", a, b, error)) << bad;
    EXPECT_NE(error.find("--frames"), std::string::npos) << error;
  }
}

TEST(Sequence, MotionFieldsAndCameraJitterReadAndRoundTrip) {
  json j = {{"format", "gblens-layout"}, {"version", 1}, {"name", "t"}, {"size", {8, 4}},
            {"targets", {{{"name", "mv"}, {"format", "rg32f"}, {"source", {{"file", "f_####.exr"}}},
                          {"quantities", {{{"quantity", "motion"}, {"name", "MV"}, {"channels", {0, 1}}, {"units", "uv"},
                                           {"y", "up"}, {"jitter", "included"}}}}}}},
            {"camera", {{"sidecar", "cam_####.json"}, {"jitter", {0.25, -0.5}}, {"time", 1.5}}}};
  Layout l;
  std::string error;
  ASSERT_TRUE(parseLayout(j, "l.json", l, error)) << error;
  const Quantity& q = l.quantities[0];
  EXPECT_TRUE(q.motionYUp);
  EXPECT_TRUE(q.jitterIncluded);
  EXPECT_EQ(l.camera.jitter.value_or(glm::dvec2(0)), glm::dvec2(0.25, -0.5));
  EXPECT_EQ(l.camera.time.value_or(0), 1.5);
  EXPECT_TRUE(hasFramePattern(l));
  const Layout f = layoutForFrame(l, 42);
  EXPECT_EQ(f.targets[0].source.path, "f_0042.exr");
  EXPECT_EQ(f.camera.sidecar, "cam_0042.json");
  Layout again;
  ASSERT_TRUE(parseLayout(layoutJson(l), "again", again, error)) << error;
  EXPECT_EQ(layoutJson(again), layoutJson(l));
  j["targets"][0]["quantities"][0]["y"] = "sideways";
  EXPECT_FALSE(parseLayout(j, "l.json", l, error));
  EXPECT_NE(error.find("y: \"sideways\" is not one of down, up"), std::string::npos) << error;
  j["targets"][0]["quantities"][0]["y"] = "up";
  j["camera"]["jitter"] = {1, 2, 3};
  EXPECT_FALSE(parseLayout(j, "l.json", l, error));
  EXPECT_NE(error.find("camera: jitter: expected [x, y] in pixels"), std::string::npos) << error;
}

// A true motion of (3, -2) px toward the previous frame, jitter delta (0.25, 0.5), a 200x100 image.
TEST(Sequence, ConventionsStoreHandComputedVectors) {
  const glm::dvec2 m(3, -2), dj(0.25, 0.5);
  MotionConvention c;
  EXPECT_EQ(storedFromMotion(c, m, dj, 200, 100), glm::dvec2(3, -2));
  c.units = MotionUnits::Uv;
  EXPECT_EQ(storedFromMotion(c, m, dj, 200, 100), glm::dvec2(0.015, -0.02));
  c.units = MotionUnits::Ndc;
  EXPECT_EQ(storedFromMotion(c, m, dj, 200, 100), glm::dvec2(0.03, -0.04));
  c.yUp = true;
  EXPECT_EQ(storedFromMotion(c, m, dj, 200, 100), glm::dvec2(0.03, 0.04));
  c = MotionConvention{};
  c.toPrevious = false;
  c.jitterIncluded = true;
  c.scale = 0.5;
  EXPECT_EQ(storedFromMotion(c, m, dj, 200, 100), glm::dvec2(-1.625, 0.75));  // -(m + dj) / 2
  EXPECT_EQ(motionFromStored(c, glm::dvec2(-1.625, 0.75), dj, 200, 100), m);
  MotionConvention declared;
  MotionDecided all{true, true, true, true, true, true};
  const std::vector<std::string> d = conventionDifferences(declared, c, all);
  ASSERT_EQ(d.size(), 3u);
  EXPECT_NE(d[0].find("direction is flipped"), std::string::npos);
  EXPECT_NE(d[1].find("half length"), std::string::npos);
  EXPECT_NE(d[2].find("jitter is included"), std::string::npos);
  MotionDecided none;
  EXPECT_TRUE(conventionDifferences(declared, c, none).empty());  // nothing undecided is ever named
}

}  // namespace
}  // namespace gb
