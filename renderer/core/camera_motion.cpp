// The camera across frames (camera_motion.h): the orbit, Halton jitter and its frame number.
#include "renderer/core/camera_motion.h"

#include <cmath>

#include <glm/gtc/constants.hpp>

namespace gb {

glm::dmat4 orbitWorldFromEye(const glm::dmat4& w0, const glm::dvec3& c, double radius, double t) {
  const double angle = glm::radians(kOrbitDegreesPerSecond) * t;
  const double rise = kOrbitRiseFraction * radius * std::sin(2.0 * glm::pi<double>() * t / kOrbitRisePeriod);
  const double cs = std::cos(angle), sn = std::sin(angle);
  glm::dmat4 rotate(1.0);  // about +Y: x' = cos x + sin z, z' = -sin x + cos z
  rotate[0] = glm::dvec4(cs, 0.0, -sn, 0.0);
  rotate[2] = glm::dvec4(sn, 0.0, cs, 0.0);
  glm::dmat4 toCentre(1.0), fromCentre(1.0), up(1.0);
  toCentre[3] = glm::dvec4(c, 1.0);
  fromCentre[3] = glm::dvec4(-c, 1.0);
  up[3] = glm::dvec4(0.0, rise, 0.0, 1.0);
  return up * toCentre * rotate * fromCentre * w0;
}

CameraDesc movedCamera(const CameraDesc& camera, const RenderOptions& o, const glm::dvec3& centre, double radius,
                       double time) {
  CameraDesc moved = camera;
  if (o.cameraMotion == CameraMotion::Orbit)
    moved.worldFromEye = orbitWorldFromEye(camera.worldFromEye, centre, radius, time);
  return moved;
}

int64_t jitterFrame(const RenderOptions& o) { return std::llround(o.time / o.timeStep); }

double halton(uint64_t index, uint32_t base) {
  double f = 1.0, r = 0.0;
  while (index > 0) {
    f /= base;
    r += f * double(index % base);
    index /= base;
  }
  return r;
}

glm::dvec2 frameJitter(const RenderOptions& o) {
  if (o.jitter == Jitter::Off) return glm::dvec2(0.0);
  const int64_t n = jitterFrame(o) % kJitterPeriod;
  const uint64_t i = uint64_t(n < 0 ? n + kJitterPeriod : n) + 1;
  return {halton(i, 2) - 0.5, halton(i, 3) - 0.5};
}

Camera jitteredCamera(const Camera& camera, const glm::dvec2& pixels) {
  Camera v = camera;
  const glm::dvec2 ndc(2.0 * pixels.x / camera.width, 2.0 * pixels.y / camera.height);
  // clip.xy += ndc * clip.w: clip w is -z (perspective: the z column) or P33 (orthographic).
  if (orthographic(camera)) {
    v.clipFromEye[3][0] += ndc.x * camera.clipFromEye[3][3];
    v.clipFromEye[3][1] += ndc.y * camera.clipFromEye[3][3];
  } else {
    v.clipFromEye[2][0] -= ndc.x;
    v.clipFromEye[2][1] -= ndc.y;
  }
  v.eyeFromClip = glm::inverse(v.clipFromEye);
  v.clipFromWorld = v.clipFromEye * v.eyeFromWorld;
  return v;
}

}  // namespace gb
