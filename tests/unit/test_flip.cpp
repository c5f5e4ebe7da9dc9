// FLIP (views/analysis/flip.h) against independent numbers: identical images give 0; uniform pairs
// (no features, the filters leave them unchanged) against the colour pipeline worked by hand from
// the paper's formulas and published CIELAB values; a synthetic pair against the numbers NVIDIA's
// reference implementation (NVlabs/flip v1.6, FLIP.h and tool/pooling.h, run once out of tree on
// these same images) gives; a local difference stays within the filters' reach.
#include <gtest/gtest.h>

#include <cmath>

#include "views/analysis/flip.h"

namespace gb {
namespace {

FlipImage uniform(uint32_t w, uint32_t h, float r, float g, float b) {
  FlipImage im{w, h, {}};
  for (size_t i = 0; i < size_t(w) * h; ++i) im.rgb.insert(im.rgb.end(), {r, g, b});
  return im;
}

// The pair the reference implementation was run on: 48x32, a colour ramp (LDR) or a radiance ramp
// with a 6-pixel checker in blue (HDR); the test image differs in x 8..19, y 10..17.
void syntheticPair(bool hdr, FlipImage& a, FlipImage& b) {
  const uint32_t w = 48, h = 32;
  a = b = FlipImage{w, h, std::vector<float>(size_t(w) * h * 3)};
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x) {
      float* p = &a.rgb[(size_t(y) * w + x) * 3];
      float* q = &b.rgb[(size_t(y) * w + x) * 3];
      const float u = x / float(w - 1), v = y / float(h - 1);
      if (!hdr) {
        p[0] = u, p[1] = v, p[2] = 0.5f * float(x + y) / float(w + h - 2);
      } else {
        p[0] = 0.02f + 30.0f * u * u * u, p[1] = 0.1f * v, p[2] = (x / 6 + y / 6) % 2 ? 5.0f : 0.01f;
      }
      for (int c = 0; c < 3; ++c) q[c] = p[c];
      if (x >= 8 && x < 20 && y >= 10 && y < 18) {
        if (!hdr) {
          q[0] = 0.9f, q[1] = 0.2f, q[2] = 0.1f;
        } else {
          q[0] = p[0] * 1.5f, q[1] = p[1] * 0.5f, q[2] = p[2] + 0.3f;
        }
      }
    }
}

// The colour pipeline's compression worked by hand (HPG 2020, section 4.1): HyAB distance d of the
// Hunt-adjusted L*a*b* colours, d^0.7 against cmax = HyAB(green, blue)^0.7 with pc = 0.4, pt = 0.95.
double compressed(double hyab) {
  // sRGB green and blue in CIELAB (D65), as published (e.g. Lindbloom's calculator):
  // green (87.735, -86.183, 83.179), blue (32.297, 79.188, -107.860); Hunt: a, b times L/100.
  const double gL = 87.735, ga = -86.183 * gL / 100, gb = 83.179 * gL / 100;
  const double bL = 32.297, ba = 79.188 * bL / 100, bb = -107.860 * bL / 100;
  const double cmax = std::pow(std::abs(gL - bL) + std::hypot(ga - ba, gb - bb), 0.7);  // ~41.27
  const double d = std::pow(hyab, 0.7), knee = 0.4 * cmax;
  return d < knee ? d * 0.95 / knee : 0.95 + (d - knee) / (cmax - knee) * 0.05;
}

// L* of a grey of linear value Y (the sRGB matrix's luminance row sums to 1); CIELAB's linear
// segment below (6/29)^3.
double greyL(double Y) {
  const double d = 6.0 / 29.0;
  return 116.0 * (Y > d * d * d ? std::cbrt(Y) : Y / (3.0 * d * d) + 4.0 / 29.0) - 16.0;
}

}  // namespace

TEST(Flip, DefaultPixelsPerDegree) {
  // 0.7 m from a 0.7 m wide, 3840-pixel monitor: 3840 pixels over 2 atan(0.5) rad, linearised as
  // the paper does: 0.7 * 3840 / 0.7 * pi / 180.
  EXPECT_NEAR(flipDefaultPpd(), 67.0206, 1e-4);
}

TEST(Flip, IdenticalImagesAreZeroEverywhere) {
  FlipImage a, b;
  syntheticPair(true, a, b);
  for (const std::vector<float>& e : {ldrFlip(b, b, flipDefaultPpd()), hdrFlip(b, b, flipDefaultPpd(), hdrFlipExposures(b))}) {
    const FlipPool p = poolFlip(e);
    EXPECT_EQ(p.mean, 0.0);
    EXPECT_EQ(p.max, 0.0);
    EXPECT_EQ(p.weightedMedian, 0.0);
  }
}

TEST(Flip, UniformPairsMatchTheColourPipelineByHand) {
  // Uniform images: no edges or points (the feature term is 0, so FLIP = the colour term), and the
  // normalised spatial filters leave them as they are. Greys have a* = b* = 0: HyAB = |dL*|.
  struct Case {
    float a, b;
  } cases[] = {{0.0f, 1.0f},     // L* 0 vs 100: above the knee, ~0.967
               {0.2f, 0.25f}};   // L* 51.84 vs 57.08: below it, ~0.183
  for (const Case& c : cases) {
    const std::vector<float> e = ldrFlip(uniform(40, 30, c.a, c.a, c.a), uniform(40, 30, c.b, c.b, c.b), 67.0);
    const double expected = compressed(std::abs(greyL(c.b) - greyL(c.a)));
    for (float v : e) ASSERT_NEAR(v, expected, 2e-4) << c.a << " vs " << c.b;
  }
  EXPECT_NEAR(compressed(100.0), 0.9674, 1e-3);  // the arithmetic above, rounded by hand
}

TEST(Flip, SyntheticPairMatchesTheReferenceImplementation) {
  // NVlabs/flip FLIP.h (default parameters, 67.02 ppd; HDR: ACES, exposures from the reference)
  // and the tool's pooling on these images.
  FlipImage a, b;
  syntheticPair(false, a, b);
  std::vector<float> e = ldrFlip(a, b, flipDefaultPpd());
  FlipPool p = poolFlip(e);
  EXPECT_NEAR(p.mean, 0.074035, 2e-5);
  EXPECT_NEAR(e[3 * 48 + 3], 0.002672, 2e-5);
  EXPECT_NEAR(e[14 * 48 + 14], 0.889718, 2e-5);
  EXPECT_NEAR(p.weightedMedian, 0.753922, 2e-5);
  EXPECT_NEAR(p.weightedQuartile1, 0.459816, 2e-5);
  EXPECT_NEAR(p.weightedQuartile3, 0.856661, 2e-5);
  EXPECT_NEAR(p.max, 0.959555, 2e-5);

  syntheticPair(true, a, b);
  const FlipExposures x = hdrFlipExposures(a);
  EXPECT_NEAR(x.start, -1.68439, 1e-4);
  EXPECT_NEAR(x.stop, 1.04585, 1e-4);
  EXPECT_EQ(x.count, 3);
  e = hdrFlip(a, b, flipDefaultPpd(), x);
  p = poolFlip(e);
  EXPECT_NEAR(p.mean, 0.041071, 2e-5);
  EXPECT_NEAR(e[3 * 48 + 3], 0.004947, 2e-5);
  EXPECT_NEAR(e[14 * 48 + 14], 0.531527, 2e-5);
}

TEST(Flip, ALocalDifferenceStaysWithinTheFiltersReach) {
  // At 67 ppd the widest filter (blue-yellow CSF) reaches ceil(3 sqrt(0.04 / (2 pi^2)) 67.02) = 10
  // pixels, the feature detectors ceil(3 * 0.5 * 0.082 * 67.02) = 9.
  FlipImage a, b;
  syntheticPair(false, a, b);
  const std::vector<float> e = ldrFlip(a, b, flipDefaultPpd());
  for (uint32_t y = 0; y < 32; ++y)
    for (uint32_t x = 0; x < 48; ++x) {
      const int dx = x < 8 ? 8 - int(x) : x > 19 ? int(x) - 19 : 0, dy = y < 10 ? 10 - int(y) : y > 17 ? int(y) - 17 : 0;
      const float v = e[size_t(y) * 48 + x];
      if (dx == 0 && dy == 0) {
        EXPECT_GT(v, 0.1f) << x << "," << y;
      } else if (std::max(dx, dy) > 10) {
        EXPECT_EQ(v, 0.0f) << x << "," << y;
      }
    }
}

TEST(Flip, PoolingWeightsByTheError) {
  // Sorted 0, 0.155, 0.245, 0.6 (sum 1): the running sums 0, 0.155, 0.4, 1.0 first exceed 0.25 at
  // 0.245, 0.5 and 0.75 at 0.6. The skipped pixel (0.9) counts nowhere.
  const FlipPool p = poolFlip({0.6f, 0.0f, 0.245f, 0.9f, 0.155f}, {0, 0, 0, 1, 0});
  EXPECT_EQ(p.pixels, 4u);
  EXPECT_NEAR(p.mean, 0.25, 1e-7);
  EXPECT_NEAR(p.weightedQuartile1, 0.245, 1e-7);
  EXPECT_NEAR(p.weightedMedian, 0.6, 1e-7);
  EXPECT_NEAR(p.weightedQuartile3, 0.6, 1e-7);
  EXPECT_EQ(p.min, 0.0);
  EXPECT_NEAR(p.max, 0.6, 1e-7);
  // Bucket 15 (0.15..0.16) holds one pixel weighted by its centre 0.155, per megapixel (4 pixels).
  EXPECT_NEAR(p.histogram[15], 0.155 / (4.0 / 1048576.0), 1e-6);
  EXPECT_NEAR(p.histogram[24], 0.245 / (4.0 / 1048576.0), 1e-6);
  EXPECT_NEAR(p.histogram[60], 0.605 / (4.0 / 1048576.0), 1e-6);
  EXPECT_EQ(p.histogram[90], 0.0);
}

TEST(Flip, MagmaEnds) {
  uint8_t lo[3], hi[3];
  magmaColor(0.0, lo);
  magmaColor(1.0, hi);
  // matplotlib's magma: (0.001462, 0.000466, 0.013866) and (0.987053, 0.991438, 0.749504).
  EXPECT_EQ(lo[0] + lo[1], 0);
  EXPECT_EQ(lo[2], 4);
  EXPECT_EQ(hi[0], 252);
  EXPECT_EQ(hi[1], 253);
  EXPECT_EQ(hi[2], 191);
}

}  // namespace gb
