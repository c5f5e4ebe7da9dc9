// The measurements of evidence.h: clear texels, surface masks, normals of rebuilt surfaces (a plane
// fitted to a window of points on one surface), angle statistics.
#include "views/infer/evidence.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <sstream>

#include "views/infer/pinhole.h"

namespace gb {

size_t SurfaceMask::count() const {
  if (at.empty()) return size_t(width) * height;
  return size_t(std::count(at.begin(), at.end(), uint8_t(1)));
}

glm::dvec4 channelValues(const CpuImage& img, uint32_t x, uint32_t y, const std::vector<uint32_t>& ch) {
  glm::dvec4 v(0.0);
  for (size_t k = 0; k < ch.size() && k < 4; ++k) v[int(k)] = img.value(x, y, ch[k]);
  return v;
}

std::array<uint32_t, 4> channelRaw(const CpuImage& img, uint32_t x, uint32_t y, const std::vector<uint32_t>& ch) {
  std::array<uint32_t, 4> r{};
  for (size_t k = 0; k < ch.size() && k < 4; ++k) r[k] = img.raw(x, y, ch[k]);
  return r;
}

ClearTexel commonTexel(const CpuImage& img) {
  ClearTexel out;
  const size_t bytes = img.texelBytes(), n = size_t(img.width) * img.height;
  if (!bytes || img.data.size() < bytes * n) return out;
  std::map<std::vector<uint8_t>, size_t> counts;
  const size_t step = std::max<size_t>(1, n / 20000);
  size_t seen = 0;
  for (size_t i = 0; i < n; i += step, ++seen)
    ++counts[std::vector<uint8_t>(img.data.begin() + long(i * bytes), img.data.begin() + long((i + 1) * bytes))];
  auto best = std::max_element(counts.begin(), counts.end(), [](auto& a, auto& b) { return a.second < b.second; });
  out.bytes = best->first;
  out.fraction = double(best->second) / double(seen);
  return out;
}

namespace {

// A texel that looks like a clear value: every channel 0, or a single channel at "infinity" (an eye
// depth's 1e10, a float's inf): not a surface's own value (a big floor's normal, albedo or material
// index is often the most common texel of its target, and is no clear value).
bool clearLike(const CpuImage& img, const std::vector<uint8_t>& bytes) {
  CpuImage one = img;
  one.width = one.height = 1;
  one.data = bytes;
  bool zero = true;
  for (uint32_t c = 0; c < img.channelCount(); ++c) zero = zero && one.value(0, 0, c) == 0.0;
  if (zero) return true;
  const double v = one.value(0, 0, 0);
  return img.channelCount() == 1 && (!std::isfinite(v) || std::abs(v) >= 1e9);
}

}  // namespace

SurfaceMask maskFromClearTexels(const std::vector<const CpuImage*>& images) {
  SurfaceMask m;
  std::vector<std::pair<const CpuImage*, ClearTexel>> cleared;
  for (const CpuImage* img : images) {
    if (!img || img->empty()) continue;
    ClearTexel c = commonTexel(*img);
    if (c.fraction > 0.02 && c.fraction < 0.98 && clearLike(*img, c.bytes)) cleared.emplace_back(img, std::move(c));
  }
  if (cleared.empty()) return m;
  m.width = cleared[0].first->width, m.height = cleared[0].first->height;
  m.at.assign(size_t(m.width) * m.height, 0);
  for (auto& [img, c] : cleared) {
    if (img->width != m.width || img->height != m.height) continue;
    const size_t bytes = img->texelBytes();
    for (size_t i = 0; i < m.at.size(); ++i)
      if (std::memcmp(img->data.data() + i * bytes, c.bytes.data(), bytes) != 0) m.at[i] = 1;
  }
  m.from = "texels that differ from the clear value of " + std::to_string(cleared.size()) + " target(s)";
  return m;
}

std::vector<glm::uvec2> samplePixels(const SurfaceMask& s, uint32_t w, uint32_t h, size_t wanted) {
  std::vector<glm::uvec2> all;
  for (uint32_t y = 2; y + 2 < h; ++y)
    for (uint32_t x = 2; x + 2 < w; ++x)
      if (s.surface(x, y)) all.push_back({x, y});
  if (all.size() <= wanted) return all;
  std::vector<glm::uvec2> out;
  const double step = double(all.size()) / double(wanted);
  for (double i = 0.0; size_t(i) < all.size(); i += step) out.push_back(all[size_t(i)]);
  return out;
}

namespace {

// The normal of a plane through the points of one surface around (x, y): the window's points
// within reach of the centre (a silhouette's other surface is far off), the covariance's smallest
// eigenvector; none when the window is not flat enough to be one surface.
std::optional<glm::dvec3> planeNormal(const PointField& points, const SurfaceMask& s, uint32_t x, uint32_t y) {
  const std::optional<glm::dvec3> c = points(x, y);
  if (!c) return std::nullopt;
  double spacing[4];
  int n4 = 0;
  const int dx[4] = {1, -1, 0, 0}, dy[4] = {0, 0, 1, -1};
  for (int k = 0; k < 4; ++k) {
    const uint32_t xx = x + dx[k], yy = y + dy[k];
    if (!s.surface(xx, yy)) return std::nullopt;
    const std::optional<glm::dvec3> p = points(xx, yy);
    if (!p) return std::nullopt;
    spacing[n4++] = glm::length(*p - *c);
  }
  std::sort(spacing, spacing + 4);
  // A step between neighbours many times the others': a depth edge through the window.
  if (!(spacing[1] > 0.0) || spacing[3] > 4.0 * spacing[1]) return std::nullopt;
  const double reach = 3.5 * spacing[2];
  std::vector<glm::dvec3> pts;
  for (int j = -2; j <= 2; ++j)
    for (int i = -2; i <= 2; ++i) {
      const uint32_t xx = x + uint32_t(i), yy = y + uint32_t(j);
      if (!s.surface(xx, yy)) continue;
      const std::optional<glm::dvec3> p = points(xx, yy);
      if (p && glm::length(*p - *c) <= reach * std::max(std::abs(i), std::abs(j))) pts.push_back(*p);
    }
  if (pts.size() < 12) return std::nullopt;
  glm::dvec3 mean(0.0);
  for (const glm::dvec3& p : pts) mean += p;
  mean /= double(pts.size());
  std::vector<double> cov(9, 0.0);
  for (const glm::dvec3& p : pts) {
    const glm::dvec3 d = p - mean;
    for (int r = 0; r < 3; ++r)
      for (int k = 0; k < 3; ++k) cov[size_t(r) * 3 + k] += d[r] * d[k];
  }
  const std::vector<double> e = smallestEigenvector(cov, 3);
  const glm::dvec3 normal = glm::normalize(glm::dvec3(e[0], e[1], e[2]));
  // Flat enough: the spread along the normal small beside the spread across the window.
  double along = 0.0, total = 0.0;
  for (const glm::dvec3& p : pts) {
    const glm::dvec3 d = p - mean;
    along += glm::dot(d, normal) * glm::dot(d, normal);
    total += glm::dot(d, d);
  }
  if (!(total > 0.0) || along > 0.02 * total) return std::nullopt;
  return normal;
}

}  // namespace

ReferenceNormals surfaceNormals(const PointField& points, const SurfaceMask& s, const std::vector<glm::uvec2>& pixels,
                                const std::optional<glm::dvec3>& eye) {
  ReferenceNormals r;
  for (const glm::uvec2& px : pixels) {
    std::optional<glm::dvec3> n = planeNormal(points, s, px.x, px.y);
    if (!n || !std::isfinite(n->x + n->y + n->z)) continue;
    if (eye) {
      const std::optional<glm::dvec3> p = points(px.x, px.y);
      if (p && glm::dot(*n, *eye - *p) < 0.0) *n = -*n;
    }
    r.pixels.push_back(px);
    r.normals.push_back(*n);
  }
  return r;
}

double quantileOf(std::vector<double> v, double q) {
  if (v.empty()) return NAN;
  const size_t k = std::min(v.size() - 1, size_t(q * double(v.size())));
  std::nth_element(v.begin(), v.begin() + long(k), v.end());
  return v[k];
}

std::string numText(double v, int digits) {
  std::ostringstream s;
  s.precision(digits);
  s << v;
  return s.str();
}

std::string AngleStats::text() const {
  return "median " + numText(median, 3) + "°, p90 " + numText(p90, 3) + "°, p99 " + numText(p99, 3) + "° over " +
         std::to_string(count) + " pixels";
}

AngleStats anglesTo(const ReferenceNormals& ref, const VectorField& candidate) {
  AngleStats a;
  std::vector<double> angles;
  size_t same = 0;
  for (size_t i = 0; i < ref.pixels.size(); ++i) {
    const std::optional<glm::dvec3> v = candidate(ref.pixels[i].x, ref.pixels[i].y);
    if (!v) continue;
    const double len = glm::length(*v);
    if (!(len > 1e-6) || !std::isfinite(len)) {
      angles.push_back(90.0);  // a zero or broken vector explains nothing
      continue;
    }
    const double c = glm::dot(*v / len, ref.normals[i]);
    same += c > 0.0;
    angles.push_back(std::acos(std::min(1.0, std::abs(c))) * 180.0 / M_PI);
  }
  a.count = angles.size();
  if (angles.empty()) return a;
  a.median = quantileOf(angles, 0.5), a.p90 = quantileOf(angles, 0.9), a.p99 = quantileOf(angles, 0.99);
  a.sameSide = double(same) / double(angles.size());
  return a;
}

}  // namespace gb
