// Orbit and fly camera. The rendered matrix stays an exact copy of the scene camera until the
// user moves: then yaw/pitch/target are derived from it once and the matrix follows them.
#include <algorithm>
#include <cmath>

#include "app/viewer/viewer.h"
#include "renderer/core/camera.h"

namespace gb {

static glm::dvec3 forwardOf(double yaw, double pitch) {
  return {std::cos(pitch) * std::sin(yaw), std::sin(pitch), -std::cos(pitch) * std::cos(yaw)};
}

void resetRig(CameraRig& rig, const CameraDesc& from, const Bounds& bounds) {
  rig.desc = from;
  rig.desc.name = "viewer";
  rig.derived = false;
  rig.sceneRadius = std::max(bounds.radius(), 1e-3);
  rig.sceneCenter = bounds.empty() ? glm::dvec3(0.0) : bounds.center();
}

static void derive(CameraRig& rig) {
  if (rig.derived) return;
  const glm::dmat4& m = rig.desc.worldFromEye;
  rig.position = glm::dvec3(m[3]);
  glm::dvec3 f = -glm::normalize(glm::dvec3(m[2]));
  rig.yaw = std::atan2(f.x, -f.z);
  rig.pitch = std::asin(std::clamp(f.y, -1.0, 1.0));
  // Orbit about the point on the view ray nearest the scene's centre (at least a little ahead).
  rig.distance = std::max(glm::dot(rig.sceneCenter - rig.position, f), 0.1 * rig.sceneRadius);
  rig.target = rig.position + f * rig.distance;
  rig.derived = true;
}

static void apply(CameraRig& rig) {
  rig.pitch = std::clamp(rig.pitch, -1.55, 1.55);
  rig.desc.worldFromEye = lookAt(rig.position, rig.position + forwardOf(rig.yaw, rig.pitch));
}

void orbitRig(CameraRig& rig, glm::dvec2 px) {
  derive(rig);
  rig.yaw += px.x * 0.006;
  rig.pitch -= px.y * 0.006;
  rig.pitch = std::clamp(rig.pitch, -1.55, 1.55);
  rig.position = rig.target - forwardOf(rig.yaw, rig.pitch) * rig.distance;
  apply(rig);
}

void lookRig(CameraRig& rig, glm::dvec2 px) {
  derive(rig);
  rig.yaw += px.x * 0.004;
  rig.pitch -= px.y * 0.004;
  rig.pitch = std::clamp(rig.pitch, -1.55, 1.55);
  rig.target = rig.position + forwardOf(rig.yaw, rig.pitch) * rig.distance;
  apply(rig);
}

void moveRig(CameraRig& rig, glm::dvec3 local) {
  derive(rig);
  glm::dvec3 f = forwardOf(rig.yaw, rig.pitch);
  glm::dvec3 right = glm::normalize(glm::cross(f, glm::dvec3(0, 1, 0)));
  glm::dvec3 d = right * local.x + glm::dvec3(0, 1, 0) * local.y - f * local.z;
  rig.position += d;
  rig.target += d;
  apply(rig);
}

void dollyRig(CameraRig& rig, double steps) {
  derive(rig);
  rig.distance = std::max(rig.distance * std::pow(0.85, steps), 1e-3 * rig.sceneRadius);
  rig.position = rig.target - forwardOf(rig.yaw, rig.pitch) * rig.distance;
  apply(rig);
}

}  // namespace gb
