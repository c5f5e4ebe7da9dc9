// Compare: idiff's exit codes on crafted captures (identical, within warn, over fail, size
// mismatch, truncated file, flipped checksum), per-target thresholds, the angular normal metric
// against a hand-computed case, manifest differences and heat maps (every group's). No GPU: the
// captures are written from synthetic frames.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "tests/support/capture_util.h"
#include "views/analysis/compare.h"

namespace gb {

namespace fs = std::filesystem;

static std::string write(const FrameSnapshot& f, const std::string& dir) {
  std::string error;
  EXPECT_TRUE(writeCapture(dir, f, CaptureMeta{}, error)) << error;
  return dir;
}

// The verdict of compareCaptures() (in process: fast) for thresholds given as CLI text.
static int verdict(const Capture& a, const Capture& b, const std::vector<std::pair<std::string, std::string>>& flags) {
  ThresholdSettings t;
  std::string error;
  for (auto& [param, value] : flags)
    if (!t.add(param, value, error)) return kCompareFileError;
  CompareReport report;
  if (!compareCaptures(a, b, t, report, error)) return kCompareFileError;
  return report.exitCode;
}

TEST(Compare, ExitCodesFollowIdiff) {
  std::string root = freshDir("compare_exit");
  FrameSnapshot base = syntheticFrame(20, 10), changed = base;
  setTexel(changed.target(Target::Hdr).image, 3, 4, 0, 2.0);
  std::string a = write(base, root + "/a"), b = write(changed, root + "/b");
  EXPECT_EQ(runGblens("compare " + a + " " + a).exitCode, kComparePass);
  EXPECT_EQ(runGblens("compare " + a + " " + b + " --warn 0.1 --fail 10").exitCode, kCompareWarn);
  EXPECT_EQ(runGblens("compare " + a + " " + b + " --warn 0.1 --fail hdr=1").exitCode, kCompareFail);

  // Size and target mismatches: exit 3.
  RunResult size = runGblens("compare " + a + " " + write(syntheticFrame(10, 10), root + "/small"));
  EXPECT_EQ(size.exitCode, kCompareMismatch);
  EXPECT_NE(size.output.find("size 20x10 vs 10x10"), std::string::npos) << size.output;
  // A target one side holds and the other did not capture: exit 3. One the other frame did not
  // compute (a feature off, as gblens render leaves coverage): skipped with its reason, the rest compared.
  FrameSnapshot fewer = base, off = base;
  fewer.target(Target::CoverageMasked) = TargetImage{};
  fewer.setAbsence(Target::CoverageMasked, Absent::NotCaptured);
  off.target(Target::CoverageMasked) = TargetImage{};
  off.setAbsence(Target::CoverageMasked, Absent::CoverageOff);
  Capture ca, cf, co;
  std::string message;
  ASSERT_TRUE(loadCapture(a, ca, message) && loadCapture(write(fewer, root + "/fewer"), cf, message) &&
              loadCapture(write(off, root + "/off"), co, message))
      << message;
  EXPECT_EQ(verdict(ca, cf, {}), kCompareMismatch);
  EXPECT_EQ(verdict(ca, co, {}), kComparePass);

  // Broken captures: exit 4 with a message that says what is wrong.
  std::string truncated = root + "/truncated", flipped = root + "/flipped";
  fs::copy(a, truncated);
  fs::copy(a, flipped);
  fs::resize_file(truncated + "/hdr.exr", fs::file_size(truncated + "/hdr.exr") / 2);
  {
    std::fstream f(flipped + "/depth.exr", std::ios::in | std::ios::out | std::ios::binary);
    f.seekg(-20, std::ios::end);
    char c = char(f.get());
    f.seekp(-20, std::ios::end);
    f.put(char(c ^ 0x01));
  }
  RunResult t = runGblens("compare " + a + " " + truncated);
  EXPECT_EQ(t.exitCode, kCompareFileError);
  EXPECT_NE(t.output.find("hdr.exr: truncated"), std::string::npos) << t.output;
  RunResult c = runGblens("compare " + flipped + " " + a);
  EXPECT_EQ(c.exitCode, kCompareFileError);
  EXPECT_NE(c.output.find("depth.exr: checksum mismatch"), std::string::npos) << c.output;
  CaptureProblem problem;
  Capture x;
  EXPECT_FALSE(loadCapture(root + "/missing", x, message, &problem));
  EXPECT_EQ(problem, CaptureProblem::Missing);
  std::ofstream(root + "/small/manifest.json") << "{ not json";
  EXPECT_FALSE(loadCapture(root + "/small", x, message, &problem));
  EXPECT_EQ(problem, CaptureProblem::Corrupt);
  EXPECT_NE(message.find("not valid JSON"), std::string::npos) << message;
  EXPECT_EQ(runGblens("compare " + a + " " + b + " --no-such-flag").exitCode, kCompareFileError);
}

TEST(Compare, NormalAngleMatchesAHandComputedCase) {
  // 10x10 normals (0, 0, 1) in A. In B: one pixel tilted to (0, 1, 1) (45 degrees), one to
  // (0, 1, 0) (90), one flipped (180), one only longer (0, 0, 2): 0 degrees, the length is not
  // an angle. All values are exact in half precision.
  FrameSnapshot fa = syntheticFrame(10, 10), fb = fa;
  CpuImage& n = fb.target(Target::NormalShadow).image;
  auto set = [&](uint32_t x, glm::dvec3 v) {
    for (int c = 0; c < 3; ++c) setTexel(n, x, 0, uint32_t(c), v[c]);
  };
  set(0, {0, 1, 1});
  set(1, {0, 1, 0});
  set(2, {0, 0, -1});
  set(3, {0, 0, 2});
  Capture a, b;
  a.frame = fa;
  b.frame = fb;
  CompareReport report;
  std::string error;
  ASSERT_TRUE(compareCaptures(a, b, ThresholdSettings{}, report, error)) << error;
  const GroupResult* g = nullptr;
  for (const GroupResult& r : report.groups)
    if (r.group.key == "normal_shadow.Normal") g = &r;
  ASSERT_NE(g, nullptr);
  EXPECT_EQ(g->group.kind, MetricKind::Normal);
  EXPECT_NEAR(g->figures.metrics["max_degrees"].get<double>(), 180.0, 1e-12);
  EXPECT_NEAR(g->figures.metrics["mean_degrees"].get<double>(), (45.0 + 90.0 + 180.0) / 100.0, 1e-12);
  // 99th percentile of 100 values: the 99th smallest, 90 degrees.
  EXPECT_NEAR(g->figures.metrics["p99_degrees"].get<double>(), 90.0, 1e-5);
  EXPECT_EQ(g->figures.metrics["differing_pixels"].get<uint64_t>(), 3u);
  EXPECT_NEAR(angleDegrees({1, 0, 0}, {1, 1e-7, 0}), 1e-7 * 180.0 / M_PI, 1e-16);  // no acos cancellation
  // The Shadow channel is its own (colour) group and did not change.
  for (const GroupResult& r : report.groups)
    if (r.group.key == "normal_shadow.Shadow") {
      EXPECT_EQ(r.figures.maxError, 0.0);
    }
}

TEST(Compare, ReportNamesOptionsThatDifferAndWritesHeatMaps) {
  std::string root = freshDir("compare_report");
  FrameSnapshot fa = syntheticFrame(16, 8), fb = fa;
  fb.options.eyeDepth = false;
  fb.options.shadowBiasSlope = 1.0f;
  setTexel(fb.target(Target::Depth).image, 5, 5, 0, 4.0);
  std::string a = write(fa, root + "/a"), b = write(fb, root + "/b");
  RunResult r = runGblens("compare " + a + " " + b + " -o " + root + "/diff --json " + root + "/report.json");
  EXPECT_EQ(r.exitCode, kCompareFail) << r.output;
  EXPECT_NE(r.output.find("options.eye_depth: \"on\" -> \"off\""), std::string::npos) << r.output;
  nlohmann::json j = nlohmann::json::parse(readText(root + "/report.json"));
  std::vector<std::string> names;
  for (auto& d : j["differences"]) names.push_back(d["name"]);
  EXPECT_NE(std::find(names.begin(), names.end(), "options.eye_depth"), names.end());
  EXPECT_NE(std::find(names.begin(), names.end(), "options.shadow_bias_slope"), names.end());
  EXPECT_EQ(j["result"], "fail");
  EXPECT_EQ(j["exit_code"], 2);
  bool depthFound = false;
  for (auto& g : j["groups"]) {
    EXPECT_TRUE(fs::exists(g["heatmap"].get<std::string>())) << g["key"];  // every group's, equal or not
    if (g["key"] != "depth") continue;
    depthFound = true;
    double expectedRel = std::abs(4.0 - double(float(2.0 + 3.0 * 5.5 / 16))) / 4.0;
    EXPECT_NEAR(g["metrics"]["max_rel"].get<double>(), expectedRel, 1e-7);
    EXPECT_EQ(g["over_fail"], 1);
      }
  EXPECT_TRUE(depthFound);
}

TEST(Compare, DecisionRuleIsIdiffs) {
  Thresholds t;
  t.fail = 0.1;
  t.failPercent = 1.0;
  t.warn = 0.01;
  t.warnPercent = 0.0;
  EXPECT_EQ(decide(t, 1000, 0, 0, 0.0), Verdict::Pass);
  EXPECT_EQ(decide(t, 1000, 1, 0, 0.05), Verdict::Warn);
  EXPECT_EQ(decide(t, 1000, 10, 10, 0.5), Verdict::Warn);  // exactly 1% over fail: allowed
  EXPECT_EQ(decide(t, 1000, 11, 11, 0.5), Verdict::Fail);
  t.hardFail = 0.4;
  EXPECT_EQ(decide(t, 1000, 1, 1, 0.5), Verdict::Fail);
}

}  // namespace gb
