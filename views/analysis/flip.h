// FLIP, the perceptual difference of two images as seen flipping between them: LDR-FLIP
// (Andersson et al., HPG 2020) and HDR-FLIP (Andersson et al., 2021), implemented from the papers,
// with the FLIP tool's pooled statistics and its magma colour map (docs/analysis.md).
#pragma once
#include <cstdint>
#include <vector>

namespace gb {

// Linear RGB, three floats a pixel, rows top to bottom.
struct FlipImage {
  uint32_t width = 0, height = 0;
  std::vector<float> rgb;
};

// Pixels per degree of visual angle for an observer `distance` metres from a monitor `monitorWidth`
// metres wide showing `pixels` columns. FLIP's default (0.7 m, 3840 px, 0.7 m) is about 67.
double flipPixelsPerDegree(double distance = 0.7, double pixels = 3840.0, double monitorWidth = 0.7);
double flipDefaultPpd();

// LDR-FLIP of two linear-RGB images in [0, 1] (values outside are clamped): the per-pixel error in
// [0, 1], 0 where they look alike.
std::vector<float> ldrFlip(const FlipImage& reference, const FlipImage& test, double ppd);

// HDR-FLIP's exposures: from `start` (the reference's largest luminance maps to 0.85 after the
// ACES tone mapper) to `stop` (its median luminance does), `count` of them evenly spaced.
struct FlipExposures {
  double start = 0.0, stop = 0.0;
  int count = 2;
};
FlipExposures hdrFlipExposures(const FlipImage& reference);
// HDR-FLIP of two linear-radiance images: each exposure tone-mapped (ACES) and clamped, LDR-FLIP of
// each, the per-pixel maximum. Non-finite and negative values count as 0.
std::vector<float> hdrFlip(const FlipImage& reference, const FlipImage& test, double ppd, const FlipExposures& e);

// The FLIP tool's pooled values over the pixels whose `skip` entry is 0 (all when `skip` is empty).
// Weighted by the error itself, as the tool does: the weighted p-th percentile is the smallest
// sorted error at which the running sum of errors exceeds p times their total; the histogram has
// 100 buckets over [0, 1], each its pixel count times its centre per megapixel (2^20 pixels).
struct FlipPool {
  uint64_t pixels = 0;
  double mean = 0.0, min = 0.0, max = 0.0;
  double weightedMedian = 0.0, weightedQuartile1 = 0.0, weightedQuartile3 = 0.0;
  std::vector<double> histogram;  // 100 buckets
};
FlipPool poolFlip(const std::vector<float>& errors, const std::vector<uint8_t>& skip = {});

// The magma colour map at v in [0, 1] (sRGB bytes), as the FLIP tool draws its error maps: entry
// magmaIndex(v) of magmaPalette() (256 entries, RGB each).
void magmaColor(double v, uint8_t out[3]);
uint8_t magmaIndex(double v);
const std::vector<uint8_t>& magmaPalette();

}  // namespace gb
