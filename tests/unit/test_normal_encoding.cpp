// Octahedral normal encodings against figures from outside the project: mean and max angular
// error over uniformly distributed unit vectors, for 8+8, 12+12 and 16+16 bits, rounded to the
// nearest code and "precise" (best of the 4 neighbouring codes; Cigolle et al., JCGT 2014). The
// Monte-Carlo here is written independently of renderer/core/codec (Gaussian directions, its own
// octahedral map in double) and must reproduce the published table; then gblens's encoder
// (octQuantize, the CPU mirror of the shader's) must pick the same codes on the same vectors.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "renderer/core/codec.h"
#include "renderer/scene/builtin.h"

namespace gb {

namespace {

// The table of issue 18 (1e6 vectors, computed outside the project): mean and max in degrees.
struct Published {
  int bits;
  double meanNearest, maxNearest, meanPrecise, maxPrecise;
};
constexpr Published kPublished[] = {{8, 0.337, 0.947, 0.315, 0.636},
                                    {12, 0.0209, 0.0587, 0.0195, 0.0393},
                                    {16, 0.00131, 0.00367, 0.00122, 0.00246}};

// Uniform unit vectors from three normal deviates (rotation invariance of the Gaussian).
std::vector<glm::dvec3> gaussianDirections(size_t n, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g;
  std::vector<glm::dvec3> out;
  out.reserve(n);
  while (out.size() < n) {
    glm::dvec3 v(g(rng), g(rng), g(rng));
    double len = std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
    if (len > 1e-6) out.push_back(v / len);
  }
  return out;
}

double sgn(double v) { return v >= 0.0 ? 1.0 : -1.0; }

// The octahedral map as Meyer et al. define it, in the "fold" form (another arrangement of the
// same map than gblens's): project onto |x|+|y|+|z| = 1, fold the lower half over the diagonals.
glm::dvec2 toOct(const glm::dvec3& v) {
  double l1 = std::abs(v.x) + std::abs(v.y) + std::abs(v.z);
  double px = v.x / l1, py = v.y / l1;
  if (v.z >= 0.0) return {px, py};
  return {(1.0 - std::abs(py)) * sgn(px), (1.0 - std::abs(px)) * sgn(py)};
}
glm::dvec3 fromOct(double px, double py) {
  double z = 1.0 - std::abs(px) - std::abs(py), t = std::max(-z, 0.0);
  glm::dvec3 v(px - t * sgn(px), py - t * sgn(py), z);
  return v / std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
}
double angleDeg(const glm::dvec3& a, const glm::dvec3& b) {
  glm::dvec3 c(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
  return std::atan2(std::sqrt(c.x * c.x + c.y * c.y + c.z * c.z), a.x * b.x + a.y * b.y + a.z * b.z) * 180.0 / M_PI;
}

struct Code {
  int x, y;
  double errorDeg;
};
Code nearestCode(const glm::dvec3& v, int bits) {
  double s = std::ldexp(1.0, bits - 1) - 1.0;
  glm::dvec2 p = toOct(v);
  int x = int(std::lround(p.x * s)), y = int(std::lround(p.y * s));
  return {x, y, angleDeg(fromOct(x / s, y / s), v)};
}
Code preciseCode(const glm::dvec3& v, int bits) {
  double s = std::ldexp(1.0, bits - 1) - 1.0;
  glm::dvec2 p = toOct(v);
  Code best{0, 0, 1e9};
  for (int dx = 0; dx <= 1; ++dx)
    for (int dy = 0; dy <= 1; ++dy) {
      int x = std::clamp(int(std::floor(p.x * s)) + dx, -int(s), int(s));
      int y = std::clamp(int(std::floor(p.y * s)) + dy, -int(s), int(s));
      double e = angleDeg(fromOct(x / s, y / s), v);
      if (e < best.errorDeg) best = {x, y, e};
    }
  return best;
}

}  // namespace

// The published table, reproduced: 1e6 Gaussian directions, mean within 2% and max within 5%
// of every entry (a maximum over a sample is itself a sample; the table's is over 1e6 as well).
TEST(NormalEncoding, IndependentMonteCarloReproducesThePublishedTable) {
  const std::vector<glm::dvec3> dirs = gaussianDirections(1000000, 18);
  for (const Published& t : kPublished) {
    double sumN = 0, maxN = 0, sumP = 0, maxP = 0;
    for (const glm::dvec3& v : dirs) {
      double n = nearestCode(v, t.bits).errorDeg, p = preciseCode(v, t.bits).errorDeg;
      sumN += n, sumP += p;
      maxN = std::max(maxN, n), maxP = std::max(maxP, p);
    }
    double meanN = sumN / dirs.size(), meanP = sumP / dirs.size();
    SCOPED_TRACE(t.bits);
    EXPECT_NEAR(meanN, t.meanNearest, 0.02 * t.meanNearest);
    EXPECT_NEAR(maxN, t.maxNearest, 0.05 * t.maxNearest);
    EXPECT_NEAR(meanP, t.meanPrecise, 0.02 * t.meanPrecise);
    EXPECT_NEAR(maxP, t.maxPrecise, 0.05 * t.maxPrecise);
    EXPECT_LT(maxP, 0.75 * maxN);  // what precise encoding is for: a third off the worst case
  }
}

// gblens's encoder (float, as the shader computes) on the same kind of vectors: nearest gives the
// independent code except where a coordinate sits within float rounding of a half code; precise
// gives a code no farther than the independent best (a different one only where two candidates
// are equally far within float precision), so its figures are the table's.
TEST(NormalEncoding, GblensEncoderPicksTheIndependentCodes) {
  const std::vector<glm::dvec3> dirs = gaussianDirections(200000, 7);
  for (int bits : {8, 12, 16}) {
    SCOPED_TRACE(bits);
    const double s = std::ldexp(1.0, bits - 1) - 1.0;
    size_t nearestDiffer = 0, preciseDiffer = 0;
    double worstExcess = 0.0;
    double sumN = 0.0, maxN = 0.0, sumP = 0.0, maxP = 0.0;  // gblens's figures
    for (const glm::dvec3& v : dirs) {
      glm::vec3 f(v);
      Code n = nearestCode(v, bits);
      glm::ivec2 gn = octQuantize(f, bits, OctEncoding::Nearest);
      if (gn.x != n.x || gn.y != n.y) {
        ++nearestDiffer;
        glm::dvec2 p = toOct(v) * s;  // only at a half code
        double half = std::min(std::abs(p.x - std::floor(p.x) - 0.5), std::abs(p.y - std::floor(p.y) - 0.5));
        EXPECT_LT(half, 5e-7 * s) << v.x << " " << v.y << " " << v.z;  // a few float ulps of p, in codes
      }
      Code p = preciseCode(v, bits);
      glm::ivec2 gp = octQuantize(f, bits, OctEncoding::Precise);
      double en = angleDeg(octDequantize(gn, bits), v), ep = angleDeg(octDequantize(gp, bits), v);
      sumN += en, sumP += ep, maxN = std::max(maxN, en), maxP = std::max(maxP, ep);
      if (gp.x != p.x || gp.y != p.y) {
        ++preciseDiffer;
        double e = angleDeg(octDequantize(gp, bits), v);
        worstExcess = std::max(worstExcess, e / p.errorDeg - 1.0);
      }
    }
    EXPECT_LT(nearestDiffer, dirs.size() / 50);
    EXPECT_LT(preciseDiffer, dirs.size() / 20);
    EXPECT_LT(worstExcess, 0.01);  // a tie within float precision, never a worse code
    // So gblens's encoder holds the published figures (within 10%; the maxima over 2e5 vectors).
    const Published& t = kPublished[bits == 8 ? 0 : bits == 12 ? 1 : 2];
    const double n = double(dirs.size());
    std::printf("gblens octQuantize %d+%d bits: nearest mean %.4g max %.4g, precise mean %.4g max %.4g (deg)\n", bits,
                bits, sumN / n, maxN, sumP / n, maxP);
    EXPECT_NEAR(sumN / n, t.meanNearest, 0.1 * t.meanNearest);
    EXPECT_NEAR(maxN, t.maxNearest, 0.1 * t.maxNearest);
    EXPECT_NEAR(sumP / n, t.meanPrecise, 0.1 * t.meanPrecise);
    EXPECT_NEAR(maxP, t.maxPrecise, 0.1 * t.maxPrecise);
  }
}

// builtin:normal-sphere's map is equal-area: equal cells of (u, v) hold equal solid angles, and
// its directions have the moments of the uniform distribution (E[z] = 0, E[z^2] = 1/3).
TEST(NormalEncoding, NormalSphereMapIsUniform) {
  const int n = 400;
  double sumZ = 0, sumZ2 = 0, sumX2 = 0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      glm::dvec3 d = normalSphereDirection((i + 0.5) / n, (j + 0.5) / n);
      EXPECT_NEAR(glm::length(d), 1.0, 1e-12);
      sumZ += d.z, sumZ2 += d.z * d.z, sumX2 += d.x * d.x;
    }
  EXPECT_NEAR(sumZ / (n * n), 0.0, 1e-9);
  EXPECT_NEAR(sumZ2 / (n * n), 1.0 / 3.0, 1e-4);
  EXPECT_NEAR(sumX2 / (n * n), 1.0 / 3.0, 1e-4);
  // A spherical cap of height h has solid angle 2 pi h: the rows v < 0.1 hold the cap z > 0.8.
  EXPECT_NEAR(normalSphereDirection(0.3, 0.1).z, 0.8, 1e-12);
}

}  // namespace gb
