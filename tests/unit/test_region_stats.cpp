// Region statistics (issue 17, section 1): the statistics of hand-computed values, and of a
// synthetic frame's rectangle against a straightforward computation over the same texels written
// here (moments, nearest-rank percentiles, NaN/Inf counts, surfaces only for decoded quantities).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "renderer/core/camera.h"
#include "tests/support/capture_util.h"
#include "views/analysis/region_stats.h"

namespace gb {
namespace {

TEST(RegionStats, HandComputedValues) {
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> v = {std::nan(""), inf, -inf, -inf};
  for (int i = 10; i >= 1; --i) v.push_back(i);  // 1..10, unsorted
  const SeriesStats s = seriesStats(v, 3);
  EXPECT_EQ(s.count, 10u);
  EXPECT_EQ(s.nan, 1u);
  EXPECT_EQ(s.posInf, 1u);
  EXPECT_EQ(s.negInf, 2u);
  EXPECT_EQ(s.min, 1.0);
  EXPECT_EQ(s.max, 10.0);
  EXPECT_DOUBLE_EQ(s.mean, 5.5);
  EXPECT_DOUBLE_EQ(s.stddev, std::sqrt(8.25));  // sum (i - 5.5)^2 / 10 = 82.5 / 10
  EXPECT_EQ(s.p1, 1.0);    // ceil(0.1) = 1st
  EXPECT_EQ(s.p50, 5.0);   // ceil(5) = 5th
  EXPECT_EQ(s.p99, 10.0);  // ceil(9.9) = 10th
  // Bins of width 3 over [1, 10]: 1-3, 4-6, 7-10 (the maximum in the last bin).
  EXPECT_EQ(s.histogram, (std::vector<uint64_t>{3, 3, 4}));
}

TEST(RegionStats, RectsAreCheckedAgainstTheFrame) {
  RegionRect r;
  std::string error;
  EXPECT_TRUE(parseRegionRect("2,3,4,5", 16, 8, r, error)) << error;
  EXPECT_EQ(r.x, 2u);
  EXPECT_EQ(r.height, 5u);
  EXPECT_FALSE(parseRegionRect("2,3,4", 16, 8, r, error));
  EXPECT_FALSE(parseRegionRect("2,3,0,5", 16, 8, r, error));
  EXPECT_FALSE(parseRegionRect("14,3,4,5", 16, 8, r, error));
  EXPECT_NE(error.find("outside the 16x8 frame"), std::string::npos) << error;
}

// A rectangle of the synthetic frame with a NaN, a +Inf and a column without a surface planted.
TEST(RegionStats, ChannelsAndQuantitiesOfARectangleOfAFrame) {
  FrameSnapshot f = syntheticFrame(24, 16);
  CpuImage& depth = f.target(Target::Depth).image;
  CpuImage& hdr = f.target(Target::Hdr).image;
  for (uint32_t y = 0; y < 16; ++y) setTexel(depth, 5, y, 0, 0.0);  // column 5: nothing drawn
  setTexel(hdr, 6, 4, 1, std::nan(""));
  setTexel(hdr, 7, 5, 1, std::numeric_limits<double>::infinity());
  const RegionRect rect{4, 3, 9, 7};
  const RegionStats s = regionStats(f, rect);
  EXPECT_EQ(s.pixels, 63u);
  EXPECT_EQ(s.surfacePixels, 56u);  // column 5 (7 pixels) has none

  // The straightforward computation: every texel of the rect (or its surfaces) in a list.
  auto expect = [&](const SeriesStats* got, std::vector<double> values, uint64_t nan, uint64_t inf) {
    ASSERT_TRUE(got);
    SCOPED_TRACE(got->target + " " + got->series);
    std::sort(values.begin(), values.end());
    const double n = double(values.size());
    double mean = 0.0, var = 0.0;
    for (double v : values) mean += v / n;
    for (double v : values) var += (v - mean) * (v - mean) / n;
    EXPECT_EQ(got->count, values.size());
    EXPECT_EQ(got->nan, nan);
    EXPECT_EQ(got->posInf, inf);
    EXPECT_EQ(got->min, values.front());
    EXPECT_EQ(got->max, values.back());
    EXPECT_NEAR(got->mean, mean, 1e-12 * std::max(1.0, std::abs(mean)));
    EXPECT_NEAR(got->stddev, std::sqrt(var), 1e-9);
    EXPECT_EQ(got->p50, values[size_t(std::ceil(0.5 * n)) - 1]);
    EXPECT_EQ(got->p99, values[size_t(std::ceil(0.99 * n)) - 1]);
    uint64_t inHistogram = 0;
    for (uint64_t c : got->histogram) inHistogram += c;
    EXPECT_EQ(inHistogram, values.size());
  };
  std::vector<double> green, eyeDepth, angle, allDepth;
  for (uint32_t y = rect.y; y < rect.y + rect.height; ++y)
    for (uint32_t x = rect.x; x < rect.x + rect.width; ++x) {
      const double g = hdr.value(x, y, 1), z = depth.value(x, y, 0);
      if (std::isfinite(g)) green.push_back(g);
      allDepth.push_back(z);
      if (z == 0.0) continue;
      eyeDepth.push_back(z);
      // N = (0, 0, 1) in eye space (rgba16f normals): the angle to the direction toward the eye.
      const glm::dvec3 toEye = -glm::normalize(eyeFromEyeDepth(f.camera, x, y, 1.0));
      angle.push_back(glm::degrees(std::acos(toEye.z)));
    }
  expect(s.channel("hdr", "G"), green, 1, 1);
  expect(s.channel("depth", "Z"), allDepth, 0, 0);        // the stored channel: every pixel
  expect(s.quantity("depth", "Depth"), eyeDepth, 0, 0);  // decoded (an eye depth as it is): surfaces
  expect(s.quantity("normal_shadow", "Normal.angle_to_view_deg"), angle, 0, 0);
  EXPECT_TRUE(s.quantity("normal_shadow", "Normal.angle_to_view_deg")->surfacesOnly);
  // Stencil is an id: a histogram of values (the synthetic frame stores 128 everywhere).
  const SeriesStats* stencil = s.quantity("depth_stencil", "Stencil");
  ASSERT_TRUE(stencil);
  ASSERT_EQ(stencil->ids.size(), 1u);
  EXPECT_EQ(stencil->ids.begin()->first, 128u);
  EXPECT_EQ(stencil->ids.begin()->second, 63u);
  // Only one target when asked.
  const RegionStats only = regionStats(f, rect, "depth");
  for (const SeriesStats& c : only.channels) EXPECT_EQ(c.target, "depth");
  EXPECT_FALSE(only.channel("hdr", "G"));
}

}  // namespace
}  // namespace gb
