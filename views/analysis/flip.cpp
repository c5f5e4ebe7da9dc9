// FLIP (flip.h), from the papers: LDR-FLIP's colour pipeline (YCxCz opponent space, the contrast
// sensitivity filters as sums of Gaussians, L*a*b* with the Hunt adjustment, the HyAB distance
// compressed by cmax, pc and pt) and feature pipeline (edges and points from first and second
// Gaussian derivatives of the achromatic channel), combined as dE_c^(1 - dE_f); HDR-FLIP's
// exposures through the ACES tone mapper; the FLIP tool's pooling. Separable filters, edges clamped.
#include "views/analysis/flip.h"

#include <algorithm>
#include <cmath>
#include <thread>

#include "renderer/core/assert.h"
#include "renderer/core/parallel_rows.h"

namespace gb {

namespace {

using Plane = std::vector<float>;

// The paper's constants: colour compression exponent, the breakpoint and its target of the error
// remapping, the feature detector's width in degrees, the feature compression exponent.
constexpr double kQc = 0.7, kPc = 0.4, kPt = 0.95, kFeatureWidth = 0.082, kQf = 0.5;
// The contrast sensitivity functions (achromatic, red-green, blue-yellow) as a1 G(b1) + a2 G(b2),
// G(b) = sqrt(pi / b) exp(-pi^2 x^2 / b), x in degrees.
constexpr double kA1[3] = {1.0, 1.0, 34.1}, kB1[3] = {0.0047, 0.0053, 0.04};
constexpr double kA2[3] = {0.0, 0.0, 13.5}, kB2[3] = {1e-5, 1e-5, 0.025};
// ACES filmic fit (x^2 c0 + x c1 + c2) / (x^2 c3 + x c4 + c5) with its 0.6 pre-exposure folded in.
constexpr double kAces[6] = {0.6 * 0.6 * 2.51, 0.6 * 0.03, 0.0, 0.6 * 0.6 * 2.43, 0.6 * 0.59, 0.14};

// Linear sRGB (D65) to CIE XYZ, exact fractions; the white point is the image of RGB (1, 1, 1).
constexpr double kRgbToXyz[3][3] = {{10135552.0 / 24577794.0, 8788810.0 / 24577794.0, 4435075.0 / 24577794.0},
                                    {2613072.0 / 12288897.0, 8788810.0 / 12288897.0, 887015.0 / 12288897.0},
                                    {1425312.0 / 73733382.0, 8788810.0 / 73733382.0, 70074185.0 / 73733382.0}};
constexpr double kXyzToRgb[3][3] = {{3.241003275, -1.537398934, -0.498615861},
                                    {-0.969224334, 1.875930071, 0.041554224},
                                    {0.055639423, -0.204011202, 1.057148933}};
constexpr double kWhite[3] = {kRgbToXyz[0][0] + kRgbToXyz[0][1] + kRgbToXyz[0][2], 1.0,
                              kRgbToXyz[2][0] + kRgbToXyz[2][1] + kRgbToXyz[2][2]};

struct Vec3 {
  double x, y, z;
};
Vec3 mul(const double m[3][3], Vec3 v) {
  return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z, m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
          m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
}
double clamp01(double v) { return std::isnan(v) ? 0.0 : std::clamp(v, 0.0, 1.0); }

// CIE L*a*b* of linear RGB, then the Hunt adjustment (chroma scaled by L*/100).
Vec3 huntLab(Vec3 rgb) {
  const Vec3 xyz = mul(kRgbToXyz, rgb);
  const double d = 6.0 / 29.0;
  auto f = [&](double t) { return t > d * d * d ? std::cbrt(t) : t / (3.0 * d * d) + 4.0 / 29.0; };
  const double fx = f(xyz.x / kWhite[0]), fy = f(xyz.y), fz = f(xyz.z / kWhite[2]);
  const double L = 116.0 * fy - 16.0;
  return {L, 0.01 * L * 500.0 * (fx - fy), 0.01 * L * 200.0 * (fy - fz)};
}
double hyab(Vec3 a, Vec3 b) { return std::abs(a.x - b.x) + std::hypot(a.y - b.y, a.z - b.z); }

// A separable convolution with a 1-D kernel of odd size, edges clamped: along rows into `tmp`, then
// columns into `dst` (added to it with `add`). The buffers are the caller's: they are reused.
void convolve(const Plane& src, uint32_t w, uint32_t h, const std::vector<float>& kx, const std::vector<float>& ky,
              Plane& tmp, Plane& dst, bool add = false) {
  const int rx = int(kx.size() / 2), ry = int(ky.size() / 2);
  tmp.resize(src.size());
  dst.resize(src.size());
  parallelRows(h, src.size(), [&](uint32_t y0, uint32_t y1) {
    std::vector<float> padded(w + 2 * rx);
    for (uint32_t y = y0; y < y1; ++y) {
      const float* row = &src[size_t(y) * w];
      for (int i = 0; i < int(padded.size()); ++i) padded[i] = row[std::clamp(i - rx, 0, int(w) - 1)];
      for (uint32_t x = 0; x < w; ++x) {
        float s = 0.0f;
        for (size_t k = 0; k < kx.size(); ++k) s += kx[k] * padded[x + k];
        tmp[size_t(y) * w + x] = s;
      }
    }
  });
  parallelRows(h, src.size(), [&](uint32_t y0, uint32_t y1) {
    for (uint32_t y = y0; y < y1; ++y) {
      float* out = &dst[size_t(y) * w];
      if (!add) std::fill(out, out + w, 0.0f);
      for (int k = -ry; k <= ry; ++k) {
        const float* in = &tmp[size_t(std::clamp(int(y) + k, 0, int(h) - 1)) * w];
        const float wk = ky[size_t(k + ry)];
        for (uint32_t x = 0; x < w; ++x) out[x] += wk * in[x];
      }
    }
  });
}

// The contrast sensitivity filters, sampled at 1/ppd degrees: per channel the 1-D factor whose
// outer product is the 2-D filter, normalised so the 2-D filter sums to 1. The blue-yellow filter,
// a sum of two Gaussians, is two separable filters whose results add.
struct SpatialFilters {
  std::vector<float> achromatic, redGreen, blueYellow1, blueYellow2;
};
SpatialFilters spatialFilters(double ppd) {
  const double maxB = std::max({kB1[0], kB1[1], kB1[2], kB2[0], kB2[1], kB2[2]});
  const int radius = int(std::ceil(3.0 * std::sqrt(maxB / (2.0 * M_PI * M_PI)) * ppd));
  std::vector<double> g[4];
  for (int i = -radius; i <= radius; ++i) {
    const double x2 = (i / ppd) * (i / ppd);
    auto gauss = [&](double a, double b) { return a * std::sqrt(M_PI / b) * std::exp(-M_PI * M_PI * x2 / b); };
    g[0].push_back(gauss(kA1[0], kB1[0]));
    g[1].push_back(gauss(kA1[1], kB1[1]));
    // Square roots of the weights: the 2-D term is the product of two 1-D factors.
    g[2].push_back(std::sqrt(kA1[2] * std::sqrt(M_PI / kB1[2])) * std::exp(-M_PI * M_PI * x2 / kB1[2]));
    g[3].push_back(std::sqrt(kA2[2] * std::sqrt(M_PI / kB2[2])) * std::exp(-M_PI * M_PI * x2 / kB2[2]));
  }
  double sum[4] = {};
  for (int k = 0; k < 4; ++k)
    for (double v : g[k]) sum[k] += v;
  const double byNorm = std::sqrt(sum[2] * sum[2] + sum[3] * sum[3]);  // 2-D sum: sum2^2 + sum3^2
  auto scaled = [](const std::vector<double>& v, double s) {
    std::vector<float> out;
    for (double x : v) out.push_back(float(x / s));
    return out;
  };
  return {scaled(g[0], sum[0]), scaled(g[1], sum[1]), scaled(g[2], byNorm), scaled(g[3], byNorm)};
}

// The feature detectors' 1-D factors in pixels: a Gaussian (sums to 1), its first and second
// derivatives (positive weights sum to 1, negative ones to -1).
struct FeatureFilters {
  std::vector<float> gauss, first, second;
};
FeatureFilters featureFilters(double ppd) {
  const double sigma = 0.5 * kFeatureWidth * ppd;
  const int radius = int(std::ceil(3.0 * sigma));
  std::vector<double> g, d1, d2;
  for (int i = -radius; i <= radius; ++i) {
    const double v = std::exp(-double(i * i) / (2.0 * sigma * sigma));
    g.push_back(v);
    d1.push_back(-i * v);
    d2.push_back((double(i * i) / (sigma * sigma) - 1.0) * v);
  }
  auto normalised = [](const std::vector<double>& v, bool split) {
    double pos = 0.0, neg = 0.0;
    for (double x : v) (x > 0.0 ? pos : neg) += std::abs(x);
    std::vector<float> out;
    for (double x : v) out.push_back(float(split ? x / (x > 0.0 ? pos : neg) : x / (pos + neg)));
    return out;
  };
  return {normalised(g, false), normalised(d1, true), normalised(d2, true)};
}

// One image through both pipelines: YCxCz (linear opponent space, D65 white) filtered by the
// contrast sensitivity functions, and the feature detectors' responses on its luminance Y/Yn.
struct Filtered {
  Plane y, cx, cz, dx, dy, ddx, ddy;
};
void filter(const FlipImage& im, const SpatialFilters& sf, const FeatureFilters& ff, Filtered& out, Plane& tmp) {
  const uint32_t w = im.width, h = im.height;
  const size_t n = size_t(w) * h;
  Plane y(n), cx(n), cz(n), gray(n);
  parallelRows(h, n, [&](uint32_t y0, uint32_t y1) {
    for (size_t i = size_t(y0) * w; i < size_t(y1) * w; ++i) {
      const float* p = &im.rgb[3 * i];
      const Vec3 xyz = mul(kRgbToXyz, {clamp01(p[0]), clamp01(p[1]), clamp01(p[2])});
      const double X = xyz.x / kWhite[0], Y = xyz.y, Z = xyz.z / kWhite[2];
      y[i] = float(116.0 * Y - 16.0);
      cx[i] = float(500.0 * (X - Y));
      cz[i] = float(200.0 * (Y - Z));
      gray[i] = float(Y);
    }
  });
  convolve(y, w, h, sf.achromatic, sf.achromatic, tmp, out.y);
  convolve(cx, w, h, sf.redGreen, sf.redGreen, tmp, out.cx);
  convolve(cz, w, h, sf.blueYellow1, sf.blueYellow1, tmp, out.cz);
  convolve(cz, w, h, sf.blueYellow2, sf.blueYellow2, tmp, out.cz, true);
  convolve(gray, w, h, ff.first, ff.gauss, tmp, out.dx);
  convolve(gray, w, h, ff.gauss, ff.first, tmp, out.dy);
  convolve(gray, w, h, ff.second, ff.gauss, tmp, out.ddx);
  convolve(gray, w, h, ff.gauss, ff.second, tmp, out.ddy);
}

// The filtered colour at pixel i back in linear RGB, clamped to [0, 1], as Hunt-adjusted L*a*b*.
Vec3 filteredLab(const Filtered& f, size_t i) {
  const double Y = (f.y[i] + 16.0) / 116.0, X = Y + f.cx[i] / 500.0, Z = Y - f.cz[i] / 200.0;
  const Vec3 c = mul(kXyzToRgb, {X * kWhite[0], Y, Z * kWhite[2]});
  return huntLab({clamp01(c.x), clamp01(c.y), clamp01(c.z)});
}

}  // namespace

double flipPixelsPerDegree(double distance, double pixels, double monitorWidth) {
  return distance * (pixels / monitorWidth) * (M_PI / 180.0);
}

double flipDefaultPpd() { return flipPixelsPerDegree(); }

std::vector<float> ldrFlip(const FlipImage& ref, const FlipImage& test, double ppd) {
  GB_ASSERT(ref.width == test.width && ref.height == test.height && ppd > 0.0);
  const SpatialFilters sf = spatialFilters(ppd);
  const FeatureFilters ff = featureFilters(ppd);
  Filtered fa, fb;
  Plane tmp;
  filter(ref, sf, ff, fa, tmp);
  filter(test, sf, ff, fb, tmp);
  // cmax: the distance between green and blue, the largest of any two colours in this space.
  const double cmax = std::pow(hyab(huntLab({0, 1, 0}), huntLab({0, 0, 1})), kQc), pccmax = kPc * cmax;
  std::vector<float> err(size_t(ref.width) * ref.height);
  parallelRows(ref.height, err.size(), [&](uint32_t y0, uint32_t y1) {
    for (size_t i = size_t(y0) * ref.width; i < size_t(y1) * ref.width; ++i) {
      double dc = std::pow(hyab(filteredLab(fa, i), filteredLab(fb, i)), kQc);
      // Errors below pc*cmax spread over [0, pt], the rest over (pt, 1].
      dc = dc < pccmax ? dc * kPt / pccmax : kPt + (dc - pccmax) / (cmax - pccmax) * (1.0 - kPt);
      const double edges = std::abs(std::hypot(fa.dx[i], fa.dy[i]) - std::hypot(fb.dx[i], fb.dy[i]));
      const double points = std::abs(std::hypot(fa.ddx[i], fa.ddy[i]) - std::hypot(fb.ddx[i], fb.ddy[i]));
      const double df = std::pow(std::max(edges, points) / std::sqrt(2.0), kQf);
      err[i] = float(std::pow(dc, 1.0 - df));
    }
  });
  return err;
}

namespace {
double luminance(const float* rgb) { return 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2]; }
float radiance(float v) { return std::isfinite(v) && v > 0.0f ? v : 0.0f; }
}  // namespace

FlipExposures hdrFlipExposures(const FlipImage& ref) {
  // The radiance x the tone mapper takes to 0.85: the larger root of (c0 - t c3) x^2 + (c1 - t c4) x + c2 - t c5.
  const double t = 0.85, a = kAces[0] - t * kAces[3], b = kAces[1] - t * kAces[4], c = kAces[2] - t * kAces[5];
  const double xMax = (-b + std::sqrt(b * b - 4.0 * a * c)) / (2.0 * a);
  std::vector<double> lum;
  for (size_t i = 0; i + 2 < ref.rgb.size(); i += 3) {
    const float px[3] = {radiance(ref.rgb[i]), radiance(ref.rgb[i + 1]), radiance(ref.rgb[i + 2])};
    lum.push_back(luminance(px));
  }
  FlipExposures e;
  if (lum.empty()) return e;
  const double yMax = *std::max_element(lum.begin(), lum.end());
  std::nth_element(lum.begin(), lum.begin() + lum.size() / 2, lum.end());
  double yMedian = lum[lum.size() / 2];
  if (!(yMax > 0.0)) return e;  // black: one exposure (twice) is as good as any
  if (!(yMedian > 0.0)) {
    // More than half the frame black (the median is undefined for exposure): the median of the lit pixels.
    std::vector<double> lit;
    for (double l : lum)
      if (l > 0.0) lit.push_back(l);
    std::nth_element(lit.begin(), lit.begin() + lit.size() / 2, lit.end());
    yMedian = lit[lit.size() / 2];
  }
  e.start = std::log2(xMax / yMax);
  e.stop = std::log2(xMax / yMedian);
  e.count = int(std::max(2.0, std::ceil(e.stop - e.start)));
  return e;
}

std::vector<float> hdrFlip(const FlipImage& ref, const FlipImage& test, double ppd, const FlipExposures& e) {
  std::vector<float> worst(size_t(ref.width) * ref.height, 0.0f);
  for (int i = 0; i < e.count; ++i) {
    const double scale = std::exp2(e.start + i * (e.stop - e.start) / (e.count - 1));
    FlipImage r = ref, t = test;
    for (FlipImage* im : {&r, &t})
      for (float& v : im->rgb) {
        const double x = radiance(v) * scale;
        v = float(clamp01((x * x * kAces[0] + x * kAces[1] + kAces[2]) / (x * x * kAces[3] + x * kAces[4] + kAces[5])));
      }
    const std::vector<float> err = ldrFlip(r, t, ppd);
    for (size_t k = 0; k < worst.size(); ++k) worst[k] = std::max(worst[k], err[k]);
  }
  return worst;
}

FlipPool poolFlip(const std::vector<float>& errors, const std::vector<uint8_t>& skip) {
  FlipPool p;
  p.histogram.assign(100, 0.0);
  std::vector<float> v;
  for (size_t i = 0; i < errors.size(); ++i)
    if ((skip.empty() || !skip[i]) && !std::isnan(errors[i])) v.push_back(errors[i]);
  if (v.empty()) return p;
  std::sort(v.begin(), v.end());
  p.pixels = v.size();
  p.min = v.front();
  p.max = v.back();
  double sum = 0.0;
  for (float e : v) sum += e;
  p.mean = sum / double(v.size());
  auto weighted = [&](double q) {
    double running = 0.0;
    for (float e : v)
      if ((running += e) > q * sum) return double(e);
    return 0.0;  // all zero
  };
  p.weightedQuartile1 = weighted(0.25);
  p.weightedMedian = weighted(0.5);
  p.weightedQuartile3 = weighted(0.75);
  const double megapixels = double(v.size()) / (1024.0 * 1024.0);
  for (float e : v) {
    const size_t b = std::min<size_t>(size_t(std::clamp(double(e), 0.0, 1.0) * 100.0), 99);
    p.histogram[b] += (b + 0.5) / 100.0 / megapixels;
  }
  return p;
}

const std::vector<uint8_t>& magmaPalette() {
  // matplotlib's magma (van der Walt and Smith), 256 entries as sRGB bytes.
  static const std::vector<uint8_t> kMagma = {
      0,   0,   4,   1,   0,   5,   1,   1,   6,   1,   1,   8,   2,   1,   9,   2,   2,  11,   2,   2,  13,   3,   3,  15,
      3,   3,  18,   4,   4,  20,   5,   4,  22,   6,   5,  24,   6,   5,  26,   7,   6,  28,   8,   7,  30,   9,   7,  32,
     10,   8,  34,  11,   9,  36,  12,   9,  38,  13,  10,  41,  14,  11,  43,  16,  11,  45,  17,  12,  47,  18,  13,  49,
     19,  13,  52,  20,  14,  54,  21,  14,  56,  22,  15,  59,  24,  15,  61,  25,  16,  63,  26,  16,  66,  28,  16,  68,
     29,  17,  71,  30,  17,  73,  32,  17,  75,  33,  17,  78,  34,  17,  80,  36,  18,  83,  37,  18,  85,  39,  18,  88,
     41,  17,  90,  42,  17,  92,  44,  17,  95,  45,  17,  97,  47,  17,  99,  49,  17, 101,  51,  16, 103,  52,  16, 105,
     54,  16, 107,  56,  16, 108,  57,  15, 110,  59,  15, 112,  61,  15, 113,  63,  15, 114,  64,  15, 116,  66,  15, 117,
     68,  15, 118,  69,  16, 119,  71,  16, 120,  73,  16, 120,  74,  16, 121,  76,  17, 122,  78,  17, 123,  79,  18, 123,
     81,  18, 124,  82,  19, 124,  84,  19, 125,  86,  20, 125,  87,  21, 126,  89,  21, 126,  90,  22, 126,  92,  22, 127,
     93,  23, 127,  95,  24, 127,  96,  24, 128,  98,  25, 128, 100,  26, 128, 101,  26, 128, 103,  27, 128, 104,  28, 129,
    106,  28, 129, 107,  29, 129, 109,  29, 129, 110,  30, 129, 112,  31, 129, 114,  31, 129, 115,  32, 129, 117,  33, 129,
    118,  33, 129, 120,  34, 129, 121,  34, 130, 123,  35, 130, 124,  35, 130, 126,  36, 130, 128,  37, 130, 129,  37, 129,
    131,  38, 129, 132,  38, 129, 134,  39, 129, 136,  39, 129, 137,  40, 129, 139,  41, 129, 140,  41, 129, 142,  42, 129,
    144,  42, 129, 145,  43, 129, 147,  43, 128, 148,  44, 128, 150,  44, 128, 152,  45, 128, 153,  45, 128, 155,  46, 127,
    156,  46, 127, 158,  47, 127, 160,  47, 127, 161,  48, 126, 163,  48, 126, 165,  49, 126, 166,  49, 125, 168,  50, 125,
    170,  51, 125, 171,  51, 124, 173,  52, 124, 174,  52, 123, 176,  53, 123, 178,  53, 123, 179,  54, 122, 181,  54, 122,
    183,  55, 121, 184,  55, 121, 186,  56, 120, 188,  57, 120, 189,  57, 119, 191,  58, 119, 192,  58, 118, 194,  59, 117,
    196,  60, 117, 197,  60, 116, 199,  61, 115, 200,  62, 115, 202,  62, 114, 204,  63, 113, 205,  64, 113, 207,  64, 112,
    208,  65, 111, 210,  66, 111, 211,  67, 110, 213,  68, 109, 214,  69, 108, 216,  69, 108, 217,  70, 107, 219,  71, 106,
    220,  72, 105, 222,  73, 104, 223,  74, 104, 224,  76, 103, 226,  77, 102, 227,  78, 101, 228,  79, 100, 229,  80, 100,
    231,  82,  99, 232,  83,  98, 233,  84,  98, 234,  86,  97, 235,  87,  96, 236,  88,  96, 237,  90,  95, 238,  91,  94,
    239,  93,  94, 240,  95,  94, 241,  96,  93, 242,  98,  93, 242, 100,  92, 243, 101,  92, 244, 103,  92, 244, 105,  92,
    245, 107,  92, 246, 108,  92, 246, 110,  92, 247, 112,  92, 247, 114,  92, 248, 116,  92, 248, 118,  92, 249, 120,  93,
    249, 121,  93, 249, 123,  93, 250, 125,  94, 250, 127,  94, 250, 129,  95, 251, 131,  95, 251, 133,  96, 251, 135,  97,
    252, 137,  97, 252, 138,  98, 252, 140,  99, 252, 142, 100, 252, 144, 101, 253, 146, 102, 253, 148, 103, 253, 150, 104,
    253, 152, 105, 253, 154, 106, 253, 155, 107, 254, 157, 108, 254, 159, 109, 254, 161, 110, 254, 163, 111, 254, 165, 113,
    254, 167, 114, 254, 169, 115, 254, 170, 116, 254, 172, 118, 254, 174, 119, 254, 176, 120, 254, 178, 122, 254, 180, 123,
    254, 182, 124, 254, 183, 126, 254, 185, 127, 254, 187, 129, 254, 189, 130, 254, 191, 132, 254, 193, 133, 254, 194, 135,
    254, 196, 136, 254, 198, 138, 254, 200, 140, 254, 202, 141, 254, 204, 143, 254, 205, 144, 254, 207, 146, 254, 209, 148,
    254, 211, 149, 254, 213, 151, 254, 215, 153, 254, 216, 154, 253, 218, 156, 253, 220, 158, 253, 222, 160, 253, 224, 161,
    253, 226, 163, 253, 227, 165, 253, 229, 167, 253, 231, 169, 253, 233, 170, 253, 235, 172, 252, 236, 174, 252, 238, 176,
    252, 240, 178, 252, 242, 180, 252, 244, 182, 252, 246, 184, 252, 247, 185, 252, 249, 187, 252, 251, 189, 252, 253, 191,
  };
  return kMagma;
}

uint8_t magmaIndex(double v) { return uint8_t(std::lround(clamp01(v) * 255.0)); }

void magmaColor(double v, uint8_t out[3]) {
  const size_t i = magmaIndex(v);
  for (int c = 0; c < 3; ++c) out[c] = magmaPalette()[i * 3 + c];
}

}  // namespace gb
