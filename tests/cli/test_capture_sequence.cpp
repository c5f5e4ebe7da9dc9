// gblens capture --sequence N: N frames at --time T, T + S, ... (S: --time-step) written as one
// sequence (sequence.json with each frame's number, time and jitter; a capture per frame that
// loadCapture opens as DIR@N), each frame's motion target stepping back to the frame before; bad
// --sequence and --time-step values refused in one line naming the flag, with nothing written.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <sstream>

#include "tests/support/capture_util.h"
#include "views/capture/capture.h"
#include "views/capture/sequence.h"

namespace gb {

namespace capture_sequence_test {

double radicalInverse(uint32_t i, uint32_t base) {
  double r = 0.0, scale = 1.0 / base;
  for (; i > 0; i /= base, scale /= base) r += scale * (i % base);
  return r;
}

// The lines of the output that are not empty.
std::vector<std::string> outputLines(const std::string& text) {
  std::vector<std::string> lines;
  std::stringstream s(text);
  for (std::string line; std::getline(s, line);)
    if (!line.empty()) lines.push_back(line);
  return lines;
}

const char* kSmall = "--size 160x90 --lights 8 --shadow-map-size 256 --validate";

}  // namespace capture_sequence_test

TEST(CaptureSequence, WritesFramesWithTimesAndJitterThatLoadAsSeqAtN) {
  using namespace capture_sequence_test;
  const std::string dir = freshDir("capture_sequence") + "/seq";
  RunResult r = runGblens(std::string("capture ") + kSmall + " --camera-motion orbit --jitter halton --motion on" +
                          " --sequence 3 --time 1 --time-step 0.1 -o " + dir);
  ASSERT_EQ(r.exitCode, 0) << r.output;
  Sequence seq;
  std::string error;
  ASSERT_TRUE(loadSequence(dir, seq, error)) << error;
  ASSERT_EQ(seq.frames.size(), 3u);
  const nlohmann::json& frames = seq.manifest["frames"];
  ASSERT_EQ(frames.size(), 3u);
  for (size_t i = 0; i < 3; ++i) {
    const SequenceFrame& f = seq.frames[i];
    EXPECT_EQ(f.number, int64_t(i));
    ASSERT_TRUE(f.time.has_value());
    EXPECT_NEAR(*f.time, 1.0 + 0.1 * double(i), 1e-12);
    // Halton(2,3) of index 1 + (round(time / time_step) mod 16): frames 10, 11, 12 -> indices 11, 12, 13.
    ASSERT_TRUE(f.jitter.has_value());
    const uint32_t index = uint32_t(std::llround(*f.time / 0.1) % 16) + 1;
    EXPECT_EQ(index, 11u + i);
    EXPECT_NEAR(f.jitter->x, radicalInverse(index, 2) - 0.5, 1e-12);
    EXPECT_NEAR(f.jitter->y, radicalInverse(index, 3) - 0.5, 1e-12);
    EXPECT_TRUE(frames[i]["jitter"].is_array());

    Capture c;
    ASSERT_TRUE(loadCapture(dir + "@" + std::to_string(i), c, error)) << error;
    EXPECT_EQ(c.manifest["options"]["time_step"], 0.1);
    EXPECT_EQ(c.manifest["options"]["jitter"], "halton");
    EXPECT_DOUBLE_EQ(c.frame.options.time, *f.time);
    EXPECT_TRUE(c.frame.target(Target::Motion).present()) << "frame " << i;
  }
  // Different frames, different cameras (the orbit), different jitter.
  EXPECT_NE(seq.frames[0].jitter->x, seq.frames[1].jitter->x);
}

TEST(CaptureSequence, BadSequenceAndTimeStepValuesFailInOneLineNamingTheFlag) {
  using namespace capture_sequence_test;
  const std::string dir = freshDir("capture_sequence_bad") + "/seq";
  const std::pair<const char*, const char*> cases[] = {{"--sequence 0", "--sequence"},
                                                       {"--sequence -2", "--sequence"},
                                                       {"--sequence two", "--sequence"},
                                                       {"--sequence 3 --time-step 0", "--time-step"},
                                                       {"--sequence 3 --time-step -0.1", "--time-step"}};
  for (auto [args, flag] : cases) {
    RunResult r = runGblens(std::string("capture ") + kSmall + " " + args + " -o " + dir);
    EXPECT_EQ(r.exitCode, 2) << args << ": " << r.output;
    const std::vector<std::string> lines = outputLines(r.output);
    ASSERT_EQ(lines.size(), 1u) << args << ": " << r.output;
    EXPECT_NE(lines[0].find(flag), std::string::npos) << lines[0];
    EXPECT_FALSE(std::filesystem::exists(dir)) << args << ": nothing may be written";
  }
}

}  // namespace gb
