// gblens attach --capture-frames A..B on tests/subjects/tiler_deferred: the application's frames A to
// B, every one, written as one sequence (views/capture/sequence.h) whose frame numbers are the
// application's own; each frame's attachments equal, bit for bit, the application's own --dump of
// that frame (its independent read-back), and SEQ@N loads frame N. Bad ranges and a range past the
// application's last frame fail in one line with nothing written. --history K (the stream's last K
// decoded frames) keeps at most K frames, their bytes counted.
#include "tests/support/test_paths.h"
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "tests/support/capture_util.h"
#include "views/capture/capture.h"
#include "views/capture/sequence.h"

namespace gb {
namespace {

using nlohmann::json;

std::string tiler() { return GBLENS_BUILD_DIR + "/tests/subjects/tiler_deferred/tiler_deferred"; }
std::string tilerLayout() { return GBLENS_SOURCE_DIR + "/tests/subjects/tiler_deferred/layout_subpass.json"; }

std::string fileBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// `gblens attach ARGS -- tiler_deferred --mode subpass --frames N` (6) with validation on (and `env`).
RunResult attachTiler(const std::string& args, const std::string& env = "", int frames = 6) {
  return runShell(env + " GBLENS_VALIDATE=1 '" + std::string(GBLENS_BINARY) + "' attach --layout '" + tilerLayout() + "' " +
                  args + " -- '" + tiler() + "' --mode subpass --frames " + std::to_string(frames));
}

// gblens's lines of the output (the application prints its own).
std::vector<std::string> gblensLines(const std::string& output) {
  std::vector<std::string> lines;
  std::istringstream in(output);
  for (std::string line; std::getline(in, line);)
    if (line.rfind("gblens", 0) == 0) lines.push_back(line);
  return lines;
}

// Target `name` of capture `c` holds exactly the dump's file (rgba8 and d32f: the capture's bytes
// are the texels as stored).
void expectDumped(const Capture& c, const std::string& name, const std::string& file) {
  SCOPED_TRACE(name);
  const int i = c.frame.indexOf(name);
  ASSERT_GE(i, 0);
  const CpuImage& img = c.frame.images[size_t(i)].image;
  const std::string bytes = fileBytes(file);
  ASSERT_EQ(img.data.size(), bytes.size());
  EXPECT_EQ(std::memcmp(img.data.data(), bytes.data(), bytes.size()), 0);
}

// tiler_deferred's own dumps of frames 2..5 (of 6) in dir/dumpK.
void dumpFrames(const std::string& dir) {
  for (int k = 2; k <= 5; ++k) {
    const RunResult dump = runShell("GBLENS_VALIDATE=1 '" + tiler() + "' --mode subpass --frames 6 --dump '" + dir + "/dump" +
                                    std::to_string(k) + "' --dump-frame " + std::to_string(k));
    ASSERT_EQ(dump.exitCode, 0) << dump.output;
  }
}

// attach --capture-frames first..last with `env` writes a sequence of exactly those frames, each
// the application's own dump of it.
void expectSequenceOfDumps(const std::string& dir, const std::string& env, int first, int last) {
  const RunResult r = attachTiler("--capture-frames " + std::to_string(first) + ".." + std::to_string(last) + " -o '" + dir +
                                  "/seq'", env);
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_EQ(r.output.find("exited with status"), std::string::npos) << r.output;  // validation clean
  const std::string count = std::to_string(last - first + 1);
  EXPECT_NE(r.output.find("wrote application frames " + std::to_string(first) + ".." + std::to_string(last) + " (" + count +
                          " frames"), std::string::npos) << r.output;
  Sequence seq;
  std::string error;
  ASSERT_TRUE(loadSequence(dir + "/seq", seq, error)) << error;
  ASSERT_EQ(seq.frames.size(), size_t(last - first + 1));
  double previous = -1.0;
  for (size_t i = 0; i < seq.frames.size(); ++i) {
    const SequenceFrame& f = seq.frames[i];
    EXPECT_EQ(f.number, int64_t(first) + int64_t(i));  // the application's numbers
    ASSERT_TRUE(f.time.has_value());                    // the layer's frame-end clock, from the first frame's end
    EXPECT_GT(*f.time, previous);
    previous = *f.time;
    EXPECT_FALSE(f.jitter.has_value());  // the stream does not say: null, never 0
  }
  EXPECT_EQ(*seq.frames[0].time, 0.0);
  EXPECT_EQ(seq.manifest["application"], "tiler_deferred") << seq.manifest.dump();
  for (int k = first; k <= last; ++k) {
    SCOPED_TRACE("frame " + std::to_string(k));
    Capture c;
    ASSERT_TRUE(loadCapture(dir + "/seq@" + std::to_string(k), c, error)) << error;
    const std::string dump = dir + "/dump" + std::to_string(k);
    ASSERT_EQ(json::parse(std::ifstream(dump + "/frame.json"))["frame"], k);
    expectDumped(c, "albedo", dump + "/albedo.bin");
    expectDumped(c, "depth", dump + "/depth.bin");
    expectDumped(c, "id", dump + "/id.bin");
    // The frame it claims to be, by the application's own count: the id's background is 0xF0000000 | k.
    uint32_t corner = 0;
    std::memcpy(&corner, c.frame.images[size_t(c.frame.indexOf("id"))].image.data.data(), 4);
    EXPECT_EQ(corner, 0xF0000000u | uint32_t(k));
  }
}

TEST(AttachSequence, CaptureFramesWritesEachFrameAsTheApplicationsOwnDumpOfIt) {
  const std::string dir = freshDir("attach_sequence");
  dumpFrames(dir);
  expectSequenceOfDumps(dir, "", 2, 4);
  // DIR@3 as any capture is taken.
  Capture c;
  std::string error;
  ASSERT_TRUE(loadCapture(dir + "/seq@3", c, error)) << error;
  // The frames differ (the camera moves each frame): a frame written three times would fail above too.
  Capture two;
  ASSERT_TRUE(loadCapture(dir + "/seq@2", two, error)) << error;
  EXPECT_NE(two.frame.images[size_t(two.frame.indexOf("depth"))].image.data,
            c.frame.images[size_t(c.frame.indexOf("depth"))].image.data);
}

// Copied out of the ring into the layer's own file (the staged ring's host buffers not shared): a
// frame done while gblens still has the one before waits for its ack instead of being dropped, and
// the range's last frame, the application's last too, is sent before its device goes.
TEST(AttachSequence, TheCopiedOutRingSendsEveryFrameUpToTheApplicationsLast) {
  const std::string dir = freshDir("attach_sequence_copied");
  dumpFrames(dir);
  expectSequenceOfDumps(dir, "GBLENS_LAYER_STAGED=1 GBLENS_LAYER_STAGED_SHARED=0", 3, 5);
  // The same through the staged ring's tile images (image-to-image copies, de-tiled by the download).
  std::filesystem::remove_all(dir + "/seq");
  expectSequenceOfDumps(dir, "GBLENS_LAYER_STAGED=1 GBLENS_LAYER_TILES=1", 3, 5);
}

TEST(AttachSequence, BadRangesAndARangePastTheLastFrameFailInOneLineWithNothingWritten) {
  const std::string dir = freshDir("attach_sequence_bad") + "/seq";
  const std::pair<std::string, std::string> cases[] = {
      {"--capture-frames 4..2", "--capture-frames 4..2"},
      {"--capture-frames two", "--capture-frames two"},
      {"--capture-frames 2..", "--capture-frames 2.."},
      {"--capture-frames -1..3", "count from 0"},
      {"--capture-frames 2..4 --capture-frame 2", "--capture-frames"},
      {"--capture-frames 2..4 --every 2", "--every"},
      {"--capture-frames 2..4 --history 2", "--history"},
      {"--capture-frames 2..4", "-o"},  // no folder
      // tiler_deferred makes frames 0..5: frame 6 never comes.
      {"--capture-frames 4..9", "before its frame 6"}};
  for (const auto& [args, says] : cases) {
    const RunResult r = attachTiler(args + (args == "--capture-frames 2..4" ? "" : " -o '" + dir + "'"));
    EXPECT_NE(r.exitCode, 0) << args << ": " << r.output;
    const std::vector<std::string> lines = gblensLines(r.output);
    ASSERT_EQ(lines.size(), 1u) << args << ": " << r.output;
    EXPECT_NE(lines[0].find(says), std::string::npos) << args << ": " << lines[0];
    EXPECT_FALSE(std::filesystem::exists(dir)) << args << ": nothing may be written";
  }
  // Nothing half-written beside it either.
  for (const auto& e : std::filesystem::directory_iterator(std::filesystem::path(dir).parent_path()))
    ADD_FAILURE() << "left behind: " << e.path();
}

// --history K on a stream of --frames: the last K frames decoded are kept with the application's
// numbers, and their memory is K frames' bytes.
TEST(AttachSequence, HistoryKeepsTheLastKFramesWithinKFramesBytes) {
  // 3 of the application's 16 frames (more than K = 2): its first frames go without copies while the
  // layer's thread makes the ring and some may be dropped under load (3 of 6 did not always come).
  const RunResult r = attachTiler("--frames 3 --history 2 --stats", "", 16);
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const size_t brace = r.output.find("{\n");
  ASSERT_NE(brace, std::string::npos) << r.output;
  const json stats = json::parse(r.output.substr(brace, r.output.rfind('}') - brace + 1), nullptr, false);
  ASSERT_TRUE(stats.is_object()) << r.output;
  const json& h = stats["history"];
  ASSERT_TRUE(h.is_object()) << stats.dump();
  EXPECT_EQ(h["limit"], 2);
  ASSERT_EQ(h["app_frames"].size(), 2u) << h.dump();
  EXPECT_LT(h["app_frames"][0].get<uint64_t>(), h["app_frames"][1].get<uint64_t>());
  EXPECT_LE(h["app_frames"][1].get<uint64_t>(), 15u);
  // Six 320x180 targets, each at least a byte a texel; both frames the same size; the sum is the bound.
  const uint64_t one = h["frame_bytes"][0];
  EXPECT_GE(one, 320u * 180u * 6u);
  EXPECT_EQ(h["frame_bytes"][1], one);
  EXPECT_EQ(h["bytes"], 2 * one);
  // Without --history nothing is kept.
  const RunResult plain = attachTiler("--frames 2 --stats", "", 16);  // 2 of 6 did not always come either
  ASSERT_EQ(plain.exitCode, 0) << plain.output;
  EXPECT_NE(plain.output.find("\"history\": null"), std::string::npos) << plain.output;
}

}  // namespace
}  // namespace gb
