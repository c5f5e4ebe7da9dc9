// Projection and reconstruction math shared by the renderer, the probe and the tests.
#include "renderer/core/camera.h"

#include <algorithm>
#include <cmath>

namespace gb {

glm::dmat4 perspective(double yfov, double aspect, double n, double f, bool reversedZ) {
  double t = 1.0 / std::tan(yfov * 0.5);
  glm::dmat4 p(0.0);
  p[0][0] = t / aspect;
  p[1][1] = -t;  // Vulkan: clip y points down, so eye +Y appears at the top of the image
  if (!reversedZ) {
    p[2][2] = f / (n - f);
    p[3][2] = n * f / (n - f);
  } else {
    p[2][2] = n / (f - n);
    p[3][2] = n * f / (f - n);
  }
  p[2][3] = -1.0;
  return p;
}

glm::dmat4 orthographicProjection(double hw, double hh, double n, double f, bool reversedZ) {
  glm::dmat4 p(1.0);
  p[0][0] = 1.0 / hw;
  p[1][1] = -1.0 / hh;  // Vulkan: clip y points down
  // depth = (z * p22 + p32): eye depth n -> 0 (1 reversed), f -> 1 (0 reversed); eye depth is -z.
  const double d0 = reversedZ ? 1.0 : 0.0, d1 = reversedZ ? 0.0 : 1.0;
  p[2][2] = -(d1 - d0) / (f - n);
  p[3][2] = d0 + p[2][2] * n;
  return p;
}

Projection projectionOf(const glm::dmat4& p) {
  // Column-major: p[c][r]. w = p[0][3] x + p[1][3] y + p[2][3] z + p[3][3]; x and y unmixed.
  if (p[0][3] != 0.0 || p[1][3] != 0.0 || p[1][0] != 0.0 || p[0][1] != 0.0 || p[0][0] == 0.0 || p[1][1] == 0.0)
    return Projection::Other;
  if (p[2][3] < 0.0 && p[3][3] == 0.0) return Projection::Perspective;
  if (p[2][3] == 0.0 && p[3][3] != 0.0) return Projection::Orthographic;
  return Projection::Other;
}

const char* name(Projection p) {
  static const char* n[] = {"perspective", "orthographic", "other"};
  return n[size_t(p)];
}

bool orthographic(const Camera& v) { return v.clipFromEye[2][3] == 0.0; }

glm::dmat4 lookAt(const glm::dvec3& eye, const glm::dvec3& target, const glm::dvec3& up) {
  glm::dvec3 back = glm::normalize(eye - target);
  glm::dvec3 right = glm::normalize(glm::cross(up, back));
  glm::dvec3 realUp = glm::cross(back, right);
  glm::dmat4 m(1.0);
  m[0] = glm::dvec4(right, 0.0);
  m[1] = glm::dvec4(realUp, 0.0);
  m[2] = glm::dvec4(back, 0.0);
  m[3] = glm::dvec4(eye, 1.0);
  return m;  // worldFromEye
}

CameraDesc lookAtCamera(std::string name, const glm::dvec3& eye, const glm::dvec3& target, double yfov,
                        double znear, double zfar) {
  CameraDesc c;
  c.name = std::move(name);
  const bool vertical = std::abs(glm::normalize(target - eye).y) > 0.999;
  c.worldFromEye = lookAt(eye, target, vertical ? glm::dvec3(0, 0, -1) : glm::dvec3(0, 1, 0));
  c.yfov = yfov;
  c.znear = znear;
  c.zfar = zfar;
  return c;
}

Camera makeCamera(const CameraDesc& camera, uint32_t width, uint32_t height, bool reversedZ) {
  Camera v;
  v.width = width;
  v.height = height;
  v.yfov = camera.yfov;
  v.aspect = camera.aspect > 0.0 ? camera.aspect : double(width) / double(height);
  v.znear = camera.znear;
  v.zfar = camera.zfar;
  v.reversedZ = reversedZ;
  v.worldFromEye = camera.worldFromEye;
  v.eyeFromWorld = glm::inverse(camera.worldFromEye);
  v.clipFromEye = perspective(v.yfov, v.aspect, v.znear, v.zfar, reversedZ);
  v.eyeFromClip = glm::inverse(v.clipFromEye);
  v.clipFromWorld = v.clipFromEye * v.eyeFromWorld;
  return v;
}

glm::dvec2 pixelNdc(const Camera& v, double px, double py) {
  return {(px + 0.5) / v.width * 2.0 - 1.0, (py + 0.5) / v.height * 2.0 - 1.0};
}

glm::dvec3 eyeFromEyeDepth(const Camera& v, double px, double py, double d) {
  glm::dvec2 ndc = pixelNdc(v, px, py);
  const glm::dmat4& p = v.clipFromEye;
  if (!orthographic(v)) return {d * (ndc.x + p[2][0]) / p[0][0], d * (ndc.y + p[2][1]) / p[1][1], -d};
  // clip = p * (x, y, -d, 1), w = p33: x = (ndc.x w - p30 + p20 d) / p00 (an oblique volume too).
  const double w = p[3][3];
  return {(ndc.x * w - p[3][0] + p[2][0] * d) / p[0][0], (ndc.y * w - p[3][1] + p[2][1] * d) / p[1][1], -d};
}

PixelRay pixelRay(const Camera& v, double px, double py) {
  PixelRay r;
  if (orthographic(v)) {
    r.origin = eyeFromEyeDepth(v, px, py, 0.0);
    r.direction = glm::normalize(eyeFromEyeDepth(v, px, py, 1.0) - r.origin);
  } else {
    r.direction = glm::normalize(eyeFromEyeDepth(v, px, py, 1.0));
  }
  return r;
}

glm::dvec3 eyeFromHardwareDepth(const Camera& v, double px, double py, double depth) {
  glm::dvec2 ndc = pixelNdc(v, px, py);
  glm::dvec4 e = v.eyeFromClip * glm::dvec4(ndc, depth, 1.0);
  return glm::dvec3(e) / e.w;
}

double hardwareDepth(const Camera& v, const glm::dvec3& eye) {
  glm::dvec4 c = v.clipFromEye * glm::dvec4(eye, 1.0);
  return c.z / c.w;
}

bool splitClipFromWorld(const glm::dmat4& m, bool clipYUp, glm::dmat4& viewFromWorld, glm::dmat4& clipFromView) {
  auto row = [&](int r) { return glm::dvec4(m[0][r], m[1][r], m[2][r], m[3][r]); };
  const glm::dvec4 rx = row(0), ry = row(1), rw = row(3);
  const glm::dvec3 toward(rw);  // clip w grows with the distance along the view direction
  if (!(glm::length(toward) > 1e-12 * std::max(glm::length(glm::dvec3(rx)), 1e-300))) return false;  // orthographic
  const glm::dmat3 rows = glm::transpose(glm::dmat3(glm::dvec3(rx), glm::dvec3(ry), glm::dvec3(rw)));
  if (!(std::abs(glm::determinant(rows)) > 1e-300)) return false;
  const glm::dvec3 eye = -glm::inverse(rows) * glm::dvec3(rx.w, ry.w, rw.w);
  const glm::dvec3 f = glm::normalize(toward);
  glm::dvec3 right = glm::dvec3(rx) - glm::dot(glm::dvec3(rx), f) * f;
  if (!(glm::length(right) > 0.0)) return false;
  right = glm::normalize(right);
  glm::dvec3 down = glm::dvec3(ry) - glm::dot(glm::dvec3(ry), f) * f - glm::dot(glm::dvec3(ry), right) * right;
  if (!(glm::length(down) > 0.0)) return false;
  down = glm::normalize(down);  // the direction clip y grows in
  const glm::dvec3 up = clipYUp ? down : -down;
  // gblens's eye: x right, y up the image, looking down -z.
  const glm::dmat3 r = glm::transpose(glm::dmat3(right, up, -f));
  viewFromWorld = glm::dmat4(r);
  viewFromWorld[3] = glm::dvec4(-(r * eye), 1.0);
  clipFromView = m * glm::inverse(viewFromWorld);
  // The terms a perspective has none of come out at float rounding, not zero: zero them (a split
  // of float matrices is good to about 1e-7 of the largest entry).
  double largest = 0.0;
  for (int c = 0; c < 4; ++c)
    for (int k = 0; k < 4; ++k) largest = std::max(largest, std::abs(clipFromView[c][k]));
  for (auto [c, k] : {std::pair{0, 1}, {1, 0}, {0, 3}, {1, 3}, {3, 3}, {3, 0}, {3, 1}, {0, 2}, {1, 2}})
    if (std::abs(clipFromView[c][k]) < 1e-5 * largest) clipFromView[c][k] = 0.0;
  return std::isfinite(glm::determinant(clipFromView));
}

}  // namespace gb
