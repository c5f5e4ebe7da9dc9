// gblens motion and flicker (issue 38) on subjects gblens did not write: tests/subjects/motion_rig (a CPU
// ray caster with its own conventions, each planted bug's convention in a hand-written truth file, and
// the exact analytic motion and visibility of every pixel) and Blender's Cycles Vector pass
// (tests/data/blender/sequence, its convention measured by assets/blender/check_vectors.py). Bugs
// planted in Blender's vectors here (sign, scale, y, a frame late) must be named; flicker planted in a
// frame must come out as its hand-computed standard deviation.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include <OpenImageIO/imageio.h>

#include "renderer/core/decode.h"
#include "renderer/core/statistics.h"
#include "tests/support/capture_util.h"
#include "tests/support/test_paths.h"
#include "views/analysis/temporal.h"
#include "views/capture/sequence.h"

namespace gb {
namespace {

using json = nlohmann::json;

std::string rigExe() { return GBLENS_BUILD_DIR + "/tests/subjects/motion_rig/motion_rig"; }
std::string rigDir() { return GBLENS_SOURCE_DIR + "/tests/subjects/motion_rig"; }

// The rig's frames for a mode, imported as a sequence: returns the sequence folder.
std::string rigSequence(const std::string& dir, const std::string& mode) {
  RunResult r = runShell("'" + rigExe() + "' --out '" + dir + "/frames' --frames 5 --bug " + mode);
  EXPECT_EQ(r.exitCode, 0) << r.output;
  std::filesystem::copy_file(rigDir() + "/layout.json", dir + "/frames/layout.json");
  r = runGblens("import --layout '" + dir + "/frames/layout.json' --frames 0..4 -o '" + dir + "/seq'");
  EXPECT_EQ(r.exitCode, 0) << r.output;
  return dir + "/seq";
}

// An EXR's float channels by name (OpenImageIO: another program's reading of the files gblens wrote).
struct ExrFloats {
  int width = 0, height = 0;
  std::vector<std::string> names;
  std::vector<float> data;
  int channel(const std::string& n) const {
    for (size_t i = 0; i < names.size(); ++i)
      if (names[i] == n) return int(i);
    return -1;
  }
  double value(int x, int y, int c) const { return data[(size_t(y) * width + x) * names.size() + size_t(c)]; }
};
bool readExrFloats(const std::string& path, ExrFloats& out, std::string& error) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) {
    error = path + ": cannot open";
    return false;
  }
  const OIIO::ImageSpec& spec = in->spec();
  out.width = spec.width, out.height = spec.height, out.names = spec.channelnames;
  out.data.resize(size_t(spec.width) * spec.height * spec.nchannels);
  const bool ok = in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, out.data.data());
  if (!ok) error = path + ": " + in->geterror();
  return ok;
}

json readJson(const std::string& path) {
  std::ifstream in(path);
  return json::parse(in);
}

TEST(MotionCli, EveryPlantedBugOfTheRigIsDetectedAndNamed) {
  // The words each finding must hold (motion.h conventionDifferences), by the field the bug changes.
  const std::map<std::string, std::string> named = {
      {"y_flipped", "y is flipped"},          {"direction_flipped", "direction is flipped"},
      {"half_scale", "half length"},          {"pixels_not_uv", "units are pixels"},
      {"one_frame_late", "one frame late"},   {"jitter_included", "jitter is included"}};
  for (const std::string mode : {"none", "y_flipped", "direction_flipped", "half_scale", "pixels_not_uv", "one_frame_late",
                                 "jitter_included"}) {
    SCOPED_TRACE(mode);
    const std::string seq = rigSequence(freshDir("motion-rig-" + mode), mode);
    const RunResult r = runGblens("motion '" + seq + "' --json");
    ASSERT_EQ(r.exitCode, mode == "none" ? 0 : 1) << r.output;
    const json report = json::parse(r.output);
    const json truth = readJson(rigDir() + "/truth/" + mode + ".json");
    EXPECT_EQ(report["verdict"], mode == "none" ? "agrees" : "differs");
    // Every decided field of every pair is the truth's; a pair may leave a field undecided (null) only
    // where it cannot be told (lag in the first pair), and the field the bug changes is decided in most.
    int decidedPairs = 0;
    for (const json& p : report["pairs"]) {
      if (p["detected"].is_null()) continue;
      ++decidedPairs;
      for (const char* field : {"units", "direction", "y", "scale", "jitter", "lag"})
        if (!p["detected"][field].is_null()) EXPECT_EQ(p["detected"][field], truth[field]) << field << " in pair " << p["current"];
      for (const char* field : {"units", "direction", "y", "scale"}) EXPECT_FALSE(p["detected"][field].is_null()) << field;
    }
    EXPECT_GE(decidedPairs, 3);
    if (mode != "none") {
      bool found = false;
      for (const json& f : report["findings"]) found = found || f.get<std::string>().find(named.at(mode)) != std::string::npos;
      EXPECT_TRUE(found) << r.output;
    } else {
      EXPECT_TRUE(report["findings"].empty()) << r.output;
    }
  }
}

// Pixel classes against the rig's own visibility (truth_mv_NNNN.exr mask: 0 sky, 1 static, 2 moving,
// 3 disoccluded) and the static error against the exact vectors.
TEST(MotionCli, ClassesAgreeWithTheRigsAnalyticVisibility) {
  const std::string dir = freshDir("motion-rig-classes");
  const std::string seq = rigSequence(dir, "none");
  const RunResult r = runGblens("motion '" + seq + "' -o '" + dir + "/maps'");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  for (int f = 1; f <= 4; ++f) {
    SCOPED_TRACE(f);
    ExrFloats maps, truth;
    std::string error;
    char name[64];
    std::snprintf(name, sizeof name, "/maps/pair_%04d.exr", f);
    ASSERT_TRUE(readExrFloats(dir + name, maps, error)) << error;
    std::snprintf(name, sizeof name, "/frames/truth_mv_%04d.exr", f);
    ASSERT_TRUE(readExrFloats(dir + name, truth, error)) << error;
    const int cls = maps.channel("motion.class"), err = maps.channel("motion.error"), mask = truth.channel("mask");
    ASSERT_GE(cls, 0);
    ASSERT_GE(mask, 0);
    uint64_t n[4] = {}, agree[4] = {};
    std::vector<double> staticErrors;
    for (int y = 0; y < maps.height; ++y)
      for (int x = 0; x < maps.width; ++x) {
        const int t = int(truth.value(x, y, mask)), c = int(maps.value(x, y, cls));
        ++n[t];
        agree[t] += (t == 0 && c == 0) || (t == 1 && c == 1) || (t == 2 && c == 2) || (t == 3 && c == 3);
        if (t == 1) staticErrors.push_back(maps.value(x, y, err));
      }
    EXPECT_EQ(agree[0], n[0]);                     // the sky is no surface
    EXPECT_GE(double(agree[1]), 0.97 * n[1]);      // static
    EXPECT_GE(double(agree[2]), 0.97 * n[2]);      // moving: N-1's G-buffer warped by the vectors agrees
    EXPECT_GE(double(agree[3]), 0.5 * n[3]);       // disoccluded
    EXPECT_LT(median(staticErrors), 1e-3);          // float32 UV vectors: far below the bound
  }
}

// The Blender fixture imported, and copies of it with a bug planted in the stored vectors.
std::string blenderSequence(const std::string& dir) {
  const RunResult r = runGblens("import '" + GBLENS_SOURCE_DIR + "/tests/data/blender/sequence/cycles_####.exr' --layout "
                                "builtin:blender-cycles-sequence --frames 1..5 -o '" + dir + "/seq'");
  EXPECT_EQ(r.exitCode, 0) << r.output;
  return dir + "/seq";
}

// Writes `seq` again with each frame's Vector.XY replaced by plant(frame index, x, y, stored) (float32).
void plantVectors(const std::string& seqDir, const std::string& out,
                  const std::function<glm::dvec2(size_t i, const std::vector<Capture>&, uint32_t x, uint32_t y)>& plant) {
  Sequence seq;
  std::string error;
  ASSERT_TRUE(loadSequence(seqDir, seq, error)) << error;
  std::vector<Capture> caps(seq.frames.size());
  for (size_t i = 0; i < caps.size(); ++i) ASSERT_TRUE(loadCapture(seq.captureDir(i), caps[i], error)) << error;
  ASSERT_TRUE(writeSequence(out, caps.size(), [&](size_t i, SequenceEntry& e, std::string&) {
    e.frame = caps[i].frame;
    e.number = seq.frames[i].number, e.time = seq.frames[i].time, e.jitter = seq.frames[i].jitter;
    const int t = e.frame.indexOf("vector");
    CpuImage& im = e.frame.images[size_t(t)].image;
    for (uint32_t y = 0; y < im.height; ++y)
      for (uint32_t x = 0; x < im.width; ++x) {
        const glm::dvec2 v = plant(i, caps, x, y);
        float* texel = reinterpret_cast<float*>(im.data.data()) + (size_t(y) * im.width + x) * im.channelCount();
        texel[0] = float(v.x), texel[1] = float(v.y);
      }
    return true;
  }, json::object(), error)) << error;
}

glm::dvec2 storedXY(const Capture& c, uint32_t x, uint32_t y) {
  const TargetImage& ti = c.frame.images[size_t(c.frame.indexOf("vector"))];
  return {ti.value(x, y, 0), ti.value(x, y, 1)};
}

TEST(MotionCli, BlendersVectorPassFollowsTheMeasuredConventionAndPlantedBugsAreNamed) {
  const std::string dir = freshDir("motion-blender");
  const std::string seq = blenderSequence(dir);
  RunResult r = runGblens("motion '" + seq + "' --json");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  json report = json::parse(r.output);
  EXPECT_EQ(report["verdict"], "agrees");
  for (const json& p : report["pairs"]) {
    EXPECT_LT(p["static_error_pixels"]["max"].get<double>(), 1e-3) << p;  // docs/accuracy.md: Blender's vectors
    EXPECT_GT(p["pixels"]["static"].get<double>(), 0.7 * p["pixels"]["surface"].get<double>()) << p;
    EXPECT_GT(p["pixels"]["moving"].get<uint64_t>(), 100u) << p;  // the Sphere and the Cube
  }
  struct Bug {
    const char* name;
    const char* words;
    std::function<glm::dvec2(size_t, const std::vector<Capture>&, uint32_t, uint32_t)> plant;
  };
  const std::vector<Bug> bugs = {
      {"sign", "direction is flipped", [](size_t i, auto& c, uint32_t x, uint32_t y) { return -storedXY(c[i], x, y); }},
      {"half", "half length", [](size_t i, auto& c, uint32_t x, uint32_t y) { return 0.5 * storedXY(c[i], x, y); }},
      {"y", "y is flipped", [](size_t i, auto& c, uint32_t x, uint32_t y) {
         const glm::dvec2 v = storedXY(c[i], x, y);
         return glm::dvec2(v.x, -v.y);
       }},
      {"late", "one frame late", [](size_t i, auto& c, uint32_t x, uint32_t y) {
         return i == 0 ? glm::dvec2(0.0) : storedXY(c[i - 1], x, y);
       }},
  };
  for (const Bug& b : bugs) {
    SCOPED_TRACE(b.name);
    const std::string planted = dir + "/planted-" + b.name;
    plantVectors(seq, planted, b.plant);
    r = runGblens("motion '" + planted + "' --json");
    EXPECT_EQ(r.exitCode, 1) << r.output;
    report = json::parse(r.output);
    bool found = false;
    for (const json& f : report["findings"]) found = found || f.get<std::string>().find(b.words) != std::string::npos;
    EXPECT_TRUE(found) << r.output;
  }
}

// Flicker planted in one frame: albedo + 0.2 in frame 2 of 5. A point every frame sees has the values
// v, v, v + 0.2, v, v: a standard deviation of sqrt(0.032 / 4) = 0.0894 and a largest step of 0.2.
TEST(FlickerCli, APlantedFlickerIsItsHandComputedDeviationAndAStaticSceneHasNone) {
  const std::string dir = freshDir("flicker-rig");
  const std::string seq = rigSequence(dir, "none");
  auto run = [&](const std::string& s, const std::string& out) {
    const RunResult r = runGblens("flicker '" + s + "' --quantity Albedo -o '" + out + "'");
    EXPECT_EQ(r.exitCode, 0) << r.output;
    ExrFloats sd, seen;
    std::string error;
    EXPECT_TRUE(readExrFloats(out + "/flicker_stddev.exr", sd, error)) << error;
    EXPECT_TRUE(readExrFloats(out + "/flicker_seen.exr", seen, error)) << error;
    std::vector<double> all;
    for (int y = 0; y < sd.height; ++y)
      for (int x = 0; x < sd.width; ++x)
        if (seen.value(x, y, 0) == 5) all.push_back(sd.value(x, y, 0));
    EXPECT_GT(all.size(), size_t(sd.width) * sd.height / 3);
    return median(all);
  };
  EXPECT_LT(run(seq, dir + "/clean"), 1e-3);
  Sequence s;
  std::string error;
  ASSERT_TRUE(loadSequence(seq, s, error)) << error;
  ASSERT_TRUE(writeSequence(dir + "/planted", s.frames.size(), [&](size_t i, SequenceEntry& e, std::string& why) {
    Capture c;
    if (!loadCapture(s.captureDir(i), c, why)) return false;
    e.frame = c.frame, e.number = s.frames[i].number, e.jitter = s.frames[i].jitter;
    if (i == 2) {
      const Quantity* q = e.frame.layout.find(QuantityKind::Albedo);
      CpuImage& im = e.frame.images[q->target].image;
      for (uint32_t y = 0; y < im.height; ++y)
        for (uint32_t x = 0; x < im.width; ++x) setTexel(im, x, y, q->channels[0], im.value(x, y, q->channels[0]) + 0.2);
    }
    return true;
  }, json::object(), error)) << error;
  EXPECT_NEAR(run(dir + "/planted", dir + "/planted-maps"), std::sqrt(0.032 / 4.0), 2e-3);
}

TEST(Sequence, AFrameIsNamedSeqAtNAndMistakesAreOneLine) {
  const std::string dir = freshDir("sequence-names");
  const std::string seq = blenderSequence(dir);
  Capture c;
  std::string error;
  ASSERT_TRUE(loadCapture(seq + "@3", c, error)) << error;
  EXPECT_EQ(c.frame.layout.camera.time.value_or(-1.0), readJson(GBLENS_SOURCE_DIR + "/tests/data/blender/sequence/camera_0003.json")["time"].get<double>());
  EXPECT_FALSE(loadCapture(seq + "@9", c, error));
  EXPECT_NE(error.find("no frame 9 (frames 1..5)"), std::string::npos) << error;
  EXPECT_FALSE(loadCapture(seq, c, error));
  EXPECT_NE(error.find("@N"), std::string::npos) << error;
  RunResult r = runGblens("probe '" + seq + "@2' 40 30 --json");
  EXPECT_EQ(r.exitCode, 0) << r.output;
  r = runGblens("import '" + GBLENS_SOURCE_DIR + "/tests/data/blender/sequence/cycles_####.exr' --layout builtin:blender-cycles-sequence -o '" +
                dir + "/one'");
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.output.find("--frames"), std::string::npos) << r.output;
  r = runGblens("import '" + GBLENS_SOURCE_DIR + "/tests/data/blender/sequence/cycles_####.exr' --layout builtin:blender-cycles-sequence "
                "--frames 3..1 -o '" + dir + "/bad'");
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.output.find("--frames 3..1"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir + "/bad"));
  r = runGblens("motion '" + dir + "/nothing'");
  EXPECT_EQ(r.exitCode, 2);
}

}  // namespace
}  // namespace gb
