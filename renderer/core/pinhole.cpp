// The direct linear transform of pinhole.h: normalised points, the homogeneous least-squares system
// solved by its smallest eigenvector, an affine (orthographic) fit beside it, and the RQ split of the
// projection into intrinsics, rotation and the eye.
#include "renderer/core/pinhole.h"

#include <algorithm>
#include <cmath>

namespace gb {

std::vector<double> smallestEigenvector(std::vector<double> a, int n) {
  std::vector<double> v(size_t(n) * n, 0.0);
  for (int i = 0; i < n; ++i) v[size_t(i) * n + i] = 1.0;
  auto at = [n](std::vector<double>& m, int r, int c) -> double& { return m[size_t(r) * n + c]; };
  for (int sweep = 0; sweep < 100; ++sweep) {
    double off = 0.0, diag = 0.0;
    for (int r = 0; r < n; ++r)
      for (int c = 0; c < n; ++c) (r == c ? diag : off) += at(a, r, c) * at(a, r, c);
    if (off <= 1e-30 * std::max(diag, 1e-300)) break;
    for (int p = 0; p < n; ++p)
      for (int q = p + 1; q < n; ++q) {
        const double apq = at(a, p, q);
        if (std::abs(apq) < 1e-300) continue;
        const double theta = (at(a, q, q) - at(a, p, p)) / (2.0 * apq);
        const double t = (theta >= 0 ? 1.0 : -1.0) / (std::abs(theta) + std::sqrt(theta * theta + 1.0));
        const double c = 1.0 / std::sqrt(t * t + 1.0), s = t * c;
        for (int k = 0; k < n; ++k) {  // a = J^T a J, columns then rows
          const double akp = at(a, k, p), akq = at(a, k, q);
          at(a, k, p) = c * akp - s * akq;
          at(a, k, q) = s * akp + c * akq;
        }
        for (int k = 0; k < n; ++k) {
          const double apk = at(a, p, k), aqk = at(a, q, k);
          at(a, p, k) = c * apk - s * aqk;
          at(a, q, k) = s * apk + c * aqk;
        }
        for (int k = 0; k < n; ++k) {
          const double vkp = at(v, k, p), vkq = at(v, k, q);
          at(v, k, p) = c * vkp - s * vkq;
          at(v, k, q) = s * vkp + c * vkq;
        }
      }
  }
  int best = 0;
  for (int i = 1; i < n; ++i)
    if (at(a, i, i) < at(a, best, best)) best = i;
  std::vector<double> out(static_cast<size_t>(n));
  for (int k = 0; k < n; ++k) out[size_t(k)] = at(v, k, best);
  return out;
}

namespace {

struct Normaliser {  // Hartley's: centroid at the origin, mean distance sqrt(dimensions)
  glm::dvec3 centre{0.0};
  double scale = 1.0;
};

template <class Get>
Normaliser normaliser(size_t n, int dims, Get get) {
  Normaliser z;
  for (size_t i = 0; i < n; ++i) z.centre += get(i);
  z.centre /= double(n);
  double mean = 0.0;
  for (size_t i = 0; i < n; ++i) mean += glm::length(get(i) - z.centre);
  mean /= double(n);
  z.scale = mean > 0.0 ? std::sqrt(double(dims)) / mean : 1.0;
  return z;
}

double quantile(std::vector<double> v, double q) {
  if (v.empty()) return INFINITY;
  const size_t k = std::min(v.size() - 1, size_t(q * double(v.size())));
  std::nth_element(v.begin(), v.begin() + long(k), v.end());
  return v[k];
}

// Reprojection distances of every sample through a 3x4 projection (a point behind it: far off).
std::vector<double> distances(const glm::dmat4x3& P, const std::vector<PointSample>& s) {
  std::vector<double> d;
  d.reserve(s.size());
  for (const PointSample& e : s) {
    const glm::dvec3 h = P * glm::dvec4(e.p, 1.0);
    if (!(std::abs(h.z) > 0.0)) {
      d.push_back(1e9);
      continue;
    }
    const double dist = glm::length(glm::dvec2(h.x / h.z - e.px, h.y / h.z - e.py));
    d.push_back(std::isfinite(dist) ? dist : 1e9);
  }
  return d;
}

// Solves the symmetric 4x4 system m x = b (Gaussian elimination with pivoting); false if singular.
bool solve4(glm::dmat4 m, glm::dvec4 b, glm::dvec4& x) {
  double a[4][5];
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) a[r][c] = m[c][r];
    a[r][4] = b[r];
  }
  for (int c = 0; c < 4; ++c) {
    int p = c;
    for (int r = c + 1; r < 4; ++r)
      if (std::abs(a[r][c]) > std::abs(a[p][c])) p = r;
    if (std::abs(a[p][c]) < 1e-300) return false;
    for (int k = 0; k < 5; ++k) std::swap(a[c][k], a[p][k]);
    for (int r = 0; r < 4; ++r) {
      if (r == c) continue;
      const double f = a[r][c] / a[c][c];
      for (int k = c; k < 5; ++k) a[r][k] -= f * a[c][k];
    }
  }
  for (int r = 0; r < 4; ++r) x[r] = a[r][4] / a[r][r];
  return true;
}

// The affine camera u = a . (p, 1), v = b . (p, 1) by least squares (orthographic projections).
bool fitAffine(const std::vector<PointSample>& s, glm::dmat4x3& P) {
  glm::dmat4 m(0.0);
  glm::dvec4 bu(0.0), bv(0.0);
  for (const PointSample& e : s) {
    const glm::dvec4 h(e.p, 1.0);
    m += glm::outerProduct(h, h);
    bu += h * e.px, bv += h * e.py;
  }
  glm::dvec4 a, b;
  if (!solve4(m, bu, a) || !solve4(m, bv, b)) return false;
  P = glm::dmat4x3(0.0);
  for (int c = 0; c < 4; ++c) P[c] = glm::dvec3(a[c], b[c], c == 3 ? 1.0 : 0.0);
  return true;
}

// K [R | t] from a perspective projection (RQ by Gram-Schmidt from the last row), scaled so that the
// points lie in front of the camera.
void decompose(PinholeFit& f, const std::vector<PointSample>& s) {
  glm::dmat4x3 P = f.projection;
  glm::dvec3 m3(P[0][2], P[1][2], P[2][2]);
  double scale = glm::length(m3);
  if (!(scale > 0.0)) return;
  size_t front = 0;
  for (const PointSample& e : s) front += (P * glm::dvec4(e.p, 1.0)).z > 0.0;
  if (front * 2 < s.size()) scale = -scale;
  P = P * (1.0 / scale);
  const glm::dvec3 m1(P[0][0], P[1][0], P[2][0]), m2(P[0][1], P[1][1], P[2][1]);
  m3 = glm::dvec3(P[0][2], P[1][2], P[2][2]);
  const glm::dvec3 r3 = m3;
  f.cy = glm::dot(m2, r3);
  glm::dvec3 r2 = m2 - f.cy * r3;
  f.fy = glm::length(r2);
  r2 /= f.fy;
  f.cx = glm::dot(m1, r3);
  f.skew = glm::dot(m1, r2);
  glm::dvec3 r1 = m1 - f.skew * r2 - f.cx * r3;
  f.fx = glm::length(r1);
  r1 /= f.fx;
  f.eyeFromPoints = glm::transpose(glm::dmat3(r1, r2, r3));  // rows r1, r2, r3
  const glm::dmat3 M = glm::transpose(glm::dmat3(m1, m2, m3));
  f.eye = -glm::inverse(M) * glm::dvec3(P[3]);
  std::vector<double> dist;
  for (const PointSample& e : s) dist.push_back(glm::length(e.p - f.eye));
  f.sceneScale = quantile(dist, 0.5);
}

}  // namespace

PinholeFit fitPinhole(const std::vector<PointSample>& all, size_t maxPoints) {
  PinholeFit f;
  std::vector<PointSample> s;
  const size_t step = std::max<size_t>(1, all.size() / std::max<size_t>(maxPoints, 1));
  for (size_t i = 0; i < all.size(); i += step)
    if (std::isfinite(all[i].p.x + all[i].p.y + all[i].p.z)) s.push_back(all[i]);
  f.points = s.size();
  if (s.size() < 12) return f;
  const Normaliser z2 = normaliser(s.size(), 2, [&](size_t i) { return glm::dvec3(s[i].px, s[i].py, 0.0); });
  const Normaliser z3 = normaliser(s.size(), 3, [&](size_t i) { return s[i].p; });
  std::vector<double> ata(144, 0.0);
  for (const PointSample& e : s) {
    const glm::dvec3 q = (e.p - z3.centre) * z3.scale;
    const double u = (e.px - z2.centre.x) * z2.scale, v = (e.py - z2.centre.y) * z2.scale;
    const double rows[2][12] = {{q.x, q.y, q.z, 1, 0, 0, 0, 0, -u * q.x, -u * q.y, -u * q.z, -u},
                                {0, 0, 0, 0, q.x, q.y, q.z, 1, -v * q.x, -v * q.y, -v * q.z, -v}};
    for (const auto& r : rows)
      for (int i = 0; i < 12; ++i)
        for (int j = 0; j < 12; ++j) ata[size_t(i) * 12 + j] += r[i] * r[j];
  }
  const std::vector<double> p = smallestEigenvector(ata, 12);
  glm::dmat4x3 Pn(0.0);  // glm: [column][row]
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) Pn[c][r] = p[size_t(r) * 4 + c];
  glm::dmat3 T2inv(1.0);  // pixel = T2^-1 * normalised pixel
  T2inv[0][0] = T2inv[1][1] = 1.0 / z2.scale;
  T2inv[2][0] = z2.centre.x, T2inv[2][1] = z2.centre.y;
  glm::dmat4 T3(z3.scale);  // normalised point = T3 * point
  T3[3] = glm::dvec4(-z3.centre * z3.scale, 1.0);
  f.projection = T2inv * Pn * T3;
  std::vector<double> d = distances(f.projection, all);
  f.medianPx = quantile(d, 0.5), f.p90Px = quantile(d, 0.9);
  glm::dmat4x3 affine;
  if (fitAffine(s, affine)) {
    std::vector<double> da = distances(affine, all);
    const double m = quantile(da, 0.5);
    // A perspective fits a parallel camera too (its last row tends to 0 0 0 c): the affine camera,
    // with fewer parameters, is taken whenever it fits about as well.
    if (m <= 1.5 * f.medianPx + 1e-3) f.projection = affine, f.medianPx = m, f.p90Px = quantile(da, 0.9), f.orthographic = true;
  }
  f.ok = std::isfinite(f.medianPx);
  if (f.ok && !f.orthographic) decompose(f, s);
  return f;
}

std::string pointSpace(const PinholeFit& f) {
  if (f.orthographic) {  // no eye: view space when the image axes are the points' own x and y
    const glm::dvec3 ax(f.projection[0][0], f.projection[1][0], f.projection[2][0]);
    const glm::dvec3 ay(f.projection[0][1], f.projection[1][1], f.projection[2][1]);
    const bool aligned = std::abs(ax.x) > 0.9999 * glm::length(ax) && std::abs(ay.y) > 0.9999 * glm::length(ay);
    return aligned ? "view" : "world";
  }
  if (glm::length(f.eye) > 2e-3 * f.sceneScale) return "world";
  for (int r = 0; r < 3; ++r) {
    const glm::dvec3 row(f.eyeFromPoints[0][r], f.eyeFromPoints[1][r], f.eyeFromPoints[2][r]);
    if (std::max({std::abs(row.x), std::abs(row.y), std::abs(row.z)}) < 0.9995) return "camera_relative";
  }
  return "view";
}

double fittedEyeDepth(const PinholeFit& f, const glm::dvec3& p) {
  const glm::dvec3 forward(f.eyeFromPoints[0][2], f.eyeFromPoints[1][2], f.eyeFromPoints[2][2]);
  return glm::dot(forward, p - f.eye);
}

}  // namespace gb
