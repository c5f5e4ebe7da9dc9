// Normals of rebuilt surfaces and angle statistics (surface_normals.h).
#include "renderer/core/surface_normals.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "renderer/core/pinhole.h"

namespace gb {

size_t SurfaceMask::count() const {
  if (at.empty()) return size_t(width) * height;
  return size_t(std::count(at.begin(), at.end(), uint8_t(1)));
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
