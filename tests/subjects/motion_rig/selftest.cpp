// motion_rig's self-check (CTest MotionRig.*, label cli): runs the program in every --bug mode and
// checks what it wrote from the files alone (README.md "Self-check"). Reads none of the program's
// code: the reprojection below is its own, from the stored depth, the sidecars' matrices and jitter.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <unistd.h>

#include <OpenImageIO/imageio.h>
#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

constexpr int kFrames = 5;
constexpr int kW = 160, kH = 96;
const char* const kBugModes[] = {"y_flipped",       "direction_flipped", "half_scale",
                                 "pixels_not_uv",   "one_frame_late",    "jitter_included",
                                 "history_stale",   "history_not_reprojected", "history_current"};

struct Exr {
  int width = 0, height = 0;
  std::map<std::string, std::vector<float>> channels;
  const std::vector<float>& operator[](const std::string& name) const {
    static const std::vector<float> none;
    auto it = channels.find(name);
    EXPECT_NE(it, channels.end()) << "no channel " << name;
    return it == channels.end() ? none : it->second;
  }
};

Exr readExr(const std::string& path) {
  Exr e;
  auto in = OIIO::ImageInput::open(path);
  if (!in) {
    ADD_FAILURE() << path << ": " << OIIO::geterror();
    return e;
  }
  const OIIO::ImageSpec& spec = in->spec();
  e.width = spec.width, e.height = spec.height;
  std::vector<float> px(size_t(spec.width) * spec.height * spec.nchannels);
  EXPECT_TRUE(in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, px.data())) << path;
  for (int c = 0; c < spec.nchannels; ++c) {
    std::vector<float>& ch = e.channels[spec.channelnames[c]];
    ch.resize(size_t(spec.width) * spec.height);
    for (size_t i = 0; i < ch.size(); ++i) ch[i] = px[i * spec.nchannels + c];
  }
  return e;
}

json readJson(const std::string& path) {
  std::ifstream f(path);
  EXPECT_TRUE(f.good()) << path;
  return json::parse(f, nullptr, false);
}

struct Cam {
  glm::dmat4 clipFromWorld{1.0};  // unjittered, d3d clip (y up, reversed z)
  glm::dvec2 jitter{0.0};         // pixels, x right, y down
  double time = 0.0;
  json raw;
};

glm::dmat4 rowMajor(const json& a) {
  glm::dmat4 m(0.0);
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) m[c][r] = a.at(r * 4 + c).get<double>();
  return m;
}

Cam readCam(const std::string& path) {
  Cam c;
  c.raw = readJson(path);
  c.clipFromWorld = rowMajor(c.raw.at("clip_from_view")) * rowMajor(c.raw.at("view_from_world"));
  c.jitter = {c.raw.at("jitter")[0].get<double>(), c.raw.at("jitter")[1].get<double>()};
  c.time = c.raw.at("time").get<double>();
  return c;
}

// Continuous pixel coordinates (x right, y down) of a homogeneous world point through an
// unjittered d3d clip_from_world.
glm::dvec2 toPixels(const glm::dmat4& clipFromWorld, const glm::dvec4& world) {
  const glm::dvec4 c = clipFromWorld * world;
  return {(c.x / c.w + 1.0) * 0.5 * kW, (1.0 - c.y / c.w) * 0.5 * kH};
}

// Halton(2, 3) minus 0.5, index (f mod 8) + 1: the README's jitter, computed here independently.
glm::dvec2 halton(int f) {
  auto inv = [](int i, int b) {
    double r = 0.0, s = 1.0 / b;
    for (; i > 0; i /= b, s /= b) r += s * (i % b);
    return r;
  };
  const int i = ((f % 8) + 8) % 8 + 1;
  return {inv(i, 2) - 0.5, inv(i, 3) - 0.5};
}

std::string name(const char* stem, int f, const char* ext) {
  char b[64];
  std::snprintf(b, sizeof b, "%s_%04d.%s", stem, f, ext);
  return b;
}

struct RigRun {
  std::vector<Exr> frames, truth;
  std::vector<Cam> cams;
};

class MotionRig : public ::testing::Test {
 protected:
  static inline std::string work;
  static inline std::map<std::string, RigRun> runs;

  static void SetUpTestSuite() {
    work = std::string(MOTION_RIG_WORK) + "/" + std::to_string(getpid());
    fs::remove_all(work);
    for (const char* mode : {"none", "y_flipped", "direction_flipped", "half_scale", "pixels_not_uv", "one_frame_late",
                             "jitter_included", "history_stale", "history_not_reprojected", "history_current"}) {
      const std::string dir = work + "/" + mode;
      const std::string cmd = std::string("'") + MOTION_RIG_EXE + "' --out '" + dir + "' --frames " +
                              std::to_string(kFrames) + " --bug " + mode + " > /dev/null";
      ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
      RigRun& r = runs[mode];
      for (int f = 0; f < kFrames; ++f) {
        r.frames.push_back(readExr(dir + "/" + name("rig", f, "exr")));
        r.truth.push_back(readExr(dir + "/" + name("truth_mv", f, "exr")));
        r.cams.push_back(readCam(dir + "/" + name("camera", f, "json")));
      }
    }
  }
  static void TearDownTestSuite() {
    runs.clear();
    fs::remove_all(work);
  }
  static glm::dvec2 storedPixels(const Exr& e, size_t i) {  // "none": uv -> pixels
    return {double(e["mv.u"][i]) * kW, double(e["mv.v"][i]) * kH};
  }
};

TEST_F(MotionRig, FilesAndSidecars) {
  const RigRun& r = runs.at("none");
  for (int f = 0; f < kFrames; ++f) {
    const Exr& e = r.frames[f];
    EXPECT_EQ(e.width, kW);
    EXPECT_EQ(e.height, kH);
    for (const char* ch : {"Z", "N.x", "N.y", "N.z", "albedo.R", "albedo.G", "albedo.B", "object", "mv.u", "mv.v", "color.R",
                           "color.G", "color.B", "hist.R", "hist.G", "hist.B"})
      EXPECT_TRUE(e.channels.count(ch)) << ch;
    const json& c = r.cams[f].raw;
    EXPECT_EQ(c.at("convention"), "d3d");
    EXPECT_EQ(c.at("up"), "z");
    EXPECT_EQ(c.at("matrix_order"), "row_major");
    EXPECT_EQ(c.at("view_handedness"), "left");
    EXPECT_EQ(c.at("image_origin"), "top");
    EXPECT_EQ(c.at("size"), json::array({kW, kH}));
    EXPECT_NEAR(r.cams[f].time, f / 30.0, 1e-12);
    EXPECT_NEAR(r.cams[f].jitter.x, halton(f).x, 1e-12) << f;
    EXPECT_NEAR(r.cams[f].jitter.y, halton(f).y, 1e-12) << f;
  }
  // The layout's sources name channels the files hold, with the frame pattern.
  const json layout = readJson(std::string(MOTION_RIG_TRUTH) + "/../layout.json");
  for (const json& t : layout.at("targets")) {
    EXPECT_EQ(t.at("source").at("file"), "rig_####.exr");
    for (const json& ch : t.at("source").at("channels")) EXPECT_TRUE(r.frames[0].channels.count(ch.get<std::string>())) << ch;
  }
  EXPECT_EQ(layout.at("camera").at("sidecar"), "camera_####.json");
}

// Static surface pixels: the stored vector is the reprojection, by hand, of depth through both cameras.
// The sky (depth 0): the reprojection of the pixel's direction (a point at infinity).
TEST_F(MotionRig, NoneMatchesReprojection) {
  const RigRun& r = runs.at("none");
  for (int f = 1; f < kFrames; ++f) {
    const Exr& e = r.frames[f];
    const Exr& t = r.truth[f];
    const glm::dmat4 worldFromClip = glm::inverse(r.cams[f].clipFromWorld);
    size_t statics = 0, sky = 0;
    double worst = 0.0;
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x) {
        const size_t i = size_t(y) * kW + x;
        const float mask = t["mask"][i];
        const double depth = e["Z"][i];
        if (mask == 0.0f) { EXPECT_EQ(depth, 0.0) << x << "," << y; }
        if (mask != 1.0f && mask != 0.0f) continue;
        // The pixel centre in the unjittered image, and its clip coordinates there.
        const glm::dvec2 u = glm::dvec2(x + 0.5, y + 0.5) - r.cams[f].jitter;
        const glm::dvec4 ndc(2.0 * u.x / kW - 1.0, 1.0 - 2.0 * u.y / kH, depth, 1.0);
        const glm::dvec4 world = worldFromClip * ndc;  // w = 0 for depth 0 (infinite far plane)
        const glm::dvec2 expected = toPixels(r.cams[f - 1].clipFromWorld, world) - u;
        const double err = glm::length(storedPixels(e, i) - expected);
        worst = std::max(worst, err);
        EXPECT_LT(err, 1e-3) << "frame " << f << " pixel " << x << "," << y << (mask == 0.0f ? " (sky)" : "");
        (mask == 0.0f ? sky : statics)++;
      }
    EXPECT_GT(statics, size_t(kW * kH / 3)) << f;
    EXPECT_GT(sky, size_t(kW * kH / 10)) << f;
    std::printf("frame %d: %zu static + %zu sky pixels, worst reprojection error %.3g px\n", f, statics, sky, worst);
  }
}

// Every pixel: the stored vector is the exact analytic motion (truth_mv); the mask agrees with ids and
// depth; moving pixels exist and do not follow the camera alone; disocclusions exist; the camera moves
// several pixels a frame.
TEST_F(MotionRig, NoneMatchesAnalyticTruth) {
  const RigRun& r = runs.at("none");
  for (int f = 0; f < kFrames; ++f) {
    const Exr& e = r.frames[f];
    const Exr& t = r.truth[f];
    size_t count[4] = {0, 0, 0, 0}, movingOffCamera = 0;
    double meanStatic = 0.0;
    const glm::dmat4 worldFromClip = glm::inverse(r.cams[f].clipFromWorld);
    for (size_t i = 0; i < size_t(kW) * kH; ++i) {
      const glm::dvec2 truth(t["mv.x"][i], t["mv.y"][i]);
      ASSERT_LT(glm::length(storedPixels(e, i) - truth), 1e-3) << "frame " << f << " texel " << i;
      const int mask = int(t["mask"][i]), id = int(e["object"][i]);
      ASSERT_TRUE(mask >= 0 && mask <= 3);
      ASSERT_EQ(float(mask), t["mask"][i]);
      ASSERT_EQ(float(id), e["object"][i]);
      ++count[mask];
      ASSERT_EQ(mask == 0, e["Z"][i] == 0.0f) << i;
      ASSERT_EQ(mask == 0, id == 0) << i;
      if (mask == 2) { ASSERT_EQ(id, 5) << i; }
      if (mask == 1) { ASSERT_NE(id, 5) << i; }
      if (mask == 1) meanStatic += glm::length(truth);
      if (mask == 2 && f > 0) {  // where the camera's motion alone would put it
        const int x = int(i % kW), y = int(i / kW);
        const glm::dvec2 u = glm::dvec2(x + 0.5, y + 0.5) - r.cams[f].jitter;
        const glm::dvec4 world = worldFromClip * glm::dvec4(2.0 * u.x / kW - 1.0, 1.0 - 2.0 * u.y / kH, e["Z"][i], 1.0);
        if (glm::length(toPixels(r.cams[f - 1].clipFromWorld, world) - u - truth) > 0.5) ++movingOffCamera;
      }
    }
    EXPECT_GT(count[2], 200u) << "moving pixels, frame " << f;
    EXPECT_GT(count[3], 20u) << "disoccluded pixels, frame " << f;
    EXPECT_GT(meanStatic / count[1], 2.0) << "mean static motion (px), frame " << f;
    if (f > 0) { EXPECT_GT(movingOffCamera, count[2] * 8 / 10) << f; }
    std::printf("frame %d: sky %zu static %zu moving %zu disoccluded %zu, mean static motion %.2f px\n", f, count[0],
                count[1], count[2], count[3], meanStatic / count[1]);
  }
}

// Each bug mode: the G-buffer is none's, and the vectors are none's turned by truth/MODE.json.
TEST_F(MotionRig, BugModesDifferAsTruthSays) {
  const RigRun& base = runs.at("none");
  for (const char* mode : kBugModes) {
    SCOPED_TRACE(mode);
    const json truth = readJson(std::string(MOTION_RIG_TRUTH) + "/" + mode + ".json");
    ASSERT_EQ(truth.at("mode"), mode);
    ASSERT_EQ(truth.size(), 8u);
    const std::string history = truth.at("history");
    ASSERT_TRUE(history == "current" || history == "previous" || history == "stale" || history == "this_frame");
    const std::string units = truth.at("units"), direction = truth.at("direction"), yAxis = truth.at("y"),
                      jitter = truth.at("jitter");
    const double scale = truth.at("scale");
    const int lag = truth.at("lag");
    ASSERT_TRUE(units == "uv" || units == "pixels" || units == "ndc");
    ASSERT_TRUE(direction == "to_previous" || direction == "to_next");
    ASSERT_TRUE(yAxis == "down" || yAxis == "up");
    ASSERT_TRUE(jitter == "excluded" || jitter == "included");
    ASSERT_TRUE(lag == 0 || lag == 1);
    const RigRun& r = runs.at(mode);
    double biggest = 0.0;
    for (int f = 0; f < kFrames; ++f) {
      const Exr& e = r.frames[f];
      for (const char* ch : {"Z", "N.x", "N.y", "N.z", "albedo.R", "albedo.G", "albedo.B", "object", "color.R", "color.G", "color.B"})
        ASSERT_EQ(e[ch], base.frames[f][ch]) << ch << " frame " << f;
      ASSERT_EQ(r.cams[f].raw, base.cams[f].raw) << f;
      if (jitter == "included" && f == 0) continue;  // frame -1's jitter is in no sidecar
      for (size_t i = 0; i < size_t(kW) * kH; ++i) {
        // The truth in pixels (to previous, y down, jitter excluded), then what the mode says.
        glm::dvec2 v(0.0);
        if (f - lag >= 0) v = storedPixels(base.frames[f - lag], i);
        if (jitter == "included") v += r.cams[f - 1].jitter - r.cams[f].jitter;
        if (direction == "to_next") v = -v;
        v *= scale;
        if (yAxis == "up") v.y = -v.y;
        if (units == "uv") v /= glm::dvec2(kW, kH);
        if (units == "ndc") v *= glm::dvec2(2.0 / kW, 2.0 / kH);
        const glm::dvec2 got(e["mv.u"][i], e["mv.v"][i]);
        const double tol = 1e-6 * std::max(1.0, glm::length(v));
        ASSERT_NEAR(got.x, v.x, tol) << "frame " << f << " texel " << i;
        ASSERT_NEAR(got.y, v.y, tol) << "frame " << f << " texel " << i;
        const glm::dvec2 plain(base.frames[f]["mv.u"][i], base.frames[f]["mv.v"][i]);
        biggest = std::max(biggest, glm::length(got - plain));
      }
    }
    if (std::string(mode).rfind("history_", 0) != 0) { EXPECT_GT(biggest, 1e-3) << "the stored vectors should differ from none's"; }
  }
}

// Bilinear sample (texel centres at i + 0.5) of a frame's colour at continuous pixel coordinates,
// clamped to the edge: how the README says the history reads the previous frame.
glm::dvec3 sampleColour(const Exr& e, glm::dvec2 at) {
  const glm::dvec2 s = at - 0.5;
  const int x0 = int(std::floor(s.x)), y0 = int(std::floor(s.y));
  const double fx = s.x - x0, fy = s.y - y0;
  auto texel = [&](int x, int y) {
    const size_t i = size_t(std::clamp(y, 0, kH - 1)) * kW + size_t(std::clamp(x, 0, kW - 1));
    return glm::dvec3(e["color.R"][i], e["color.G"][i], e["color.B"][i]);
  };
  return (texel(x0, y0) * (1 - fx) + texel(x0 + 1, y0) * fx) * (1 - fy) + (texel(x0, y0 + 1) * (1 - fx) + texel(x0 + 1, y0 + 1) * fx) * fy;
}

glm::dvec3 hist(const Exr& e, size_t i) { return {e["hist.R"][i], e["hist.G"][i], e["hist.B"][i]}; }
glm::dvec3 colour(const Exr& e, size_t i) { return {e["color.R"][i], e["color.G"][i], e["color.B"][i]}; }
bool nearHalf(glm::dvec3 a, glm::dvec3 b) {  // within a half float's rounding
  for (int k = 0; k < 3; ++k)
    if (std::fabs(a[k] - b[k]) > 1e-3 * std::fabs(b[k]) + 1e-6) return false;
  return true;
}

// Mode none: frame 0's history is zero; at every static and sky pixel of frames 1.. it is frame N-1's
// colour sampled where the reprojection by hand (depth, both sidecars, both jitters) puts the point.
TEST_F(MotionRig, HistoryIsThePreviousColourReprojected) {
  const RigRun& r = runs.at("none");
  for (size_t i = 0; i < size_t(kW) * kH; ++i) ASSERT_EQ(hist(r.frames[0], i), glm::dvec3(0.0)) << i;
  for (int f = 1; f < kFrames; ++f) {
    const glm::dmat4 worldFromClip = glm::inverse(r.cams[f].clipFromWorld);
    size_t checked = 0, differ = 0;
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x) {
        const size_t i = size_t(y) * kW + x;
        const float mask = r.truth[f]["mask"][i];
        if (mask != 1.0f && mask != 0.0f) continue;
        const glm::dvec2 u = glm::dvec2(x + 0.5, y + 0.5) - r.cams[f].jitter;
        const glm::dvec4 world = worldFromClip * glm::dvec4(2.0 * u.x / kW - 1.0, 1.0 - 2.0 * u.y / kH, r.frames[f]["Z"][i], 1.0);
        const glm::dvec2 at = toPixels(r.cams[f - 1].clipFromWorld, world) + r.cams[f - 1].jitter;
        const glm::dvec3 want = sampleColour(r.frames[f - 1], at);
        ASSERT_TRUE(nearHalf(hist(r.frames[f], i), want)) << "frame " << f << " pixel " << x << "," << y;
        ++checked;
        differ += !nearHalf(hist(r.frames[f], i), colour(r.frames[f - 1], i)) && mask == 1.0f;
      }
    EXPECT_GT(checked, size_t(kW * kH / 2)) << f;
    EXPECT_GT(differ, checked / 2) << "reprojected and not reprojected histories should differ, frame " << f;
  }
}

// The history modes: what truth/MODE.json's "history" says, from mode none's files.
TEST_F(MotionRig, HistoryModesHoldWhatTheTruthSays) {
  const RigRun& base = runs.at("none");
  for (const char* mode : kBugModes) {
    SCOPED_TRACE(mode);
    const std::string history = readJson(std::string(MOTION_RIG_TRUTH) + "/" + mode + ".json").at("history");
    const RigRun& r = runs.at(mode);
    for (size_t i = 0; i < size_t(kW) * kH; ++i) ASSERT_EQ(hist(r.frames[0], i), glm::dvec3(0.0)) << "frame 0 is zero";
    for (int f = 1; f < kFrames; ++f)
      for (size_t i = 0; i < size_t(kW) * kH; ++i) {
        const glm::dvec3 got = hist(r.frames[f], i);
        if (history == "current") ASSERT_EQ(got, hist(base.frames[f], i)) << f << " " << i;
        if (history == "stale") ASSERT_EQ(got, hist(base.frames[f - 1], i)) << f << " " << i;
        if (history == "previous") ASSERT_TRUE(nearHalf(got, colour(base.frames[f - 1], i))) << f << " " << i;
        if (history == "this_frame") ASSERT_TRUE(nearHalf(got, colour(base.frames[f], i))) << f << " " << i;
      }
  }
}

}  // namespace
