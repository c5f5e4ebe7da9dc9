// Compare across storage formats: the same frame captured with two normal formats, or with standard
// and reversed depth, compares within the formats' quantisation bounds (each side decoded with its own
// layout), not by raw channels. The bounds are derived here from the formats, by hand.
#include <gtest/gtest.h>

#include <cmath>

#include "tests/support/capture_util.h"
#include "views/analysis/compare.h"

namespace gb {

namespace {

const char* kFrame = "--size 96x54 --lights 8 --shadow-map-size 128";

// Captures the frame with `options` into dir/name and loads it.
Capture captured(const std::string& dir, const std::string& name, const std::string& options) {
  Capture c;
  RunResult r = runGblens(std::string("capture ") + kFrame + " " + options + " -o '" + dir + "/" + name + "'");
  EXPECT_EQ(r.exitCode, 0) << r.output;
  std::string error;
  EXPECT_TRUE(loadCapture(dir + "/" + name, c, error)) << error;
  return c;
}

const GroupResult* group(const CompareReport& r, const std::string& key) {
  for (const GroupResult& g : r.groups)
    if (g.group.key == key) return &g;
  return nullptr;
}

CompareReport compared(const Capture& a, const Capture& b) {
  CompareReport report;
  std::string error;
  EXPECT_TRUE(compareCaptures(a, b, ThresholdSettings{}, report, error)) << error;
  return report;
}

// Worst angle (degrees) a format's rounding turns a unit normal by. Per component the error is at
// most half a step e; the three components together move the vector by at most e * sqrt(3)
// (rgba8 snorm: e = 0.5 / 127), or for half floats by 2^-11 relative to each component, i.e. at
// most 2^-11 of the unit length. Octahedral 16+16 (snorm, round to nearest): 0.00367 degrees
// (Cigolle et al., JCGT 2014, table of the survey; measured outside the project).
constexpr double kDeg = 180.0 / M_PI;
const double kRgba16fWorst = std::ldexp(1.0, -11) * kDeg;
const double kRgba8SnormWorst = 0.5 / 127.0 * std::sqrt(3.0) * kDeg;
const double kOct16Worst = 0.00367;

}  // namespace

TEST(CompareFormats, TwoNormalFormatsCompareWithinTheirQuantisation) {
  const std::string dir = freshDir("compare-normal-formats");
  Capture oct = captured(dir, "oct", "--normal-format oct-rg16");
  Capture half = captured(dir, "half", "--normal-format rgba16f");
  Capture snorm8 = captured(dir, "snorm8", "--normal-format rgba8-snorm");
  for (auto [other, bound] : {std::pair{&half, kRgba16fWorst + kOct16Worst}, {&snorm8, kRgba8SnormWorst + kOct16Worst}}) {
    CompareReport r = compared(oct, *other);
    EXPECT_TRUE(r.mismatches.empty()) << r.text();
    const GroupResult* n = group(r, "normal_shadow.Normal");
    ASSERT_NE(n, nullptr) << r.text();
    EXPECT_EQ(n->group.kind, MetricKind::Normal);
    EXPECT_GT(n->figures.pixels, 0u);
    EXPECT_EQ(n->figures.coverageDiffers, 0u);
    EXPECT_LE(n->figures.maxError, bound) << r.text();
    EXPECT_GT(n->figures.maxError, 0.0) << "two formats cannot round every normal alike";
    // The shadow term shares the normal's target: half a step of the coarser format on each side
    // (rgba8 snorm: 0.5 / 127; 16-bit snorm and half are finer).
    const GroupResult* s = group(r, "normal_shadow.Shadow");
    ASSERT_NE(s, nullptr);
    EXPECT_LE(s->figures.maxError, 0.5 / 127.0 + 0.5 / 32767.0 + std::ldexp(1.0, -11)) << r.text();
  }
}

TEST(CompareFormats, StandardAndReversedDepthCompareAsEyeDepthWithinTheirRounding) {
  const std::string dir = freshDir("compare-depth-encodings");
  Capture standard = captured(dir, "standard", "--reversed-z off");
  Capture reversed = captured(dir, "reversed", "--reversed-z on");
  CompareReport r = compared(standard, reversed);
  const GroupResult* g = group(r, "depth_stencil.HardwareDepth");
  ASSERT_NE(g, nullptr) << r.text();
  EXPECT_EQ(g->figures.coverageDiffers, 0u) << r.text();
  EXPECT_GT(g->figures.pixels, 0u);
  // Both store float depth; compared raw they would differ by ~100 % (d and 1 - d). As eye depth
  // the difference is the rounding of the standard side, whose values crowd below 1: with
  // d = f (z - n) / (z (f - n)), a depth error dd moves the eye depth by
  // dz / z = dd z (f - n) / (f n) <= dd (f - n) / n. dd: the rasterizer's interpolation and the
  // float store, allowed 4 ulps of values in [0.5, 1) (2^-22); the reversed side is far finer.
  const double n = standard.frame.camera.znear, f = standard.frame.camera.zfar;
  EXPECT_LE(g->figures.metrics["max_rel"].get<double>(), std::ldexp(1.0, -22) * (f - n) / n) << r.text();
  EXPECT_GT(g->figures.maxError, 0.0);
  // The stencil is an integer in both: exact.
  const GroupResult* s = group(r, "depth_stencil.Stencil");
  ASSERT_NE(s, nullptr);
  EXPECT_EQ(s->figures.maxError, 0.0);
}

}  // namespace gb
