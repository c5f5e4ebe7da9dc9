// Scenes for the stress cases, built in code: a floor with boxes, camera placement, and moving a
// whole scene (camera included) away from the origin.
#include <cmath>

#include "app/stress/stress.h"
#include "renderer/core/camera.h"
#include "renderer/scene/mesh_builder.h"

namespace gb::stress {

Scene groundScene(double halfSize, bool sun) {
  Scene s;
  s.source = "stress:ground";
  MaterialDesc floor;
  floor.name = "floor";
  floor.baseColor = glm::vec4(0.5f, 0.5f, 0.5f, 1.0f);
  floor.specular = 0.3f;
  MaterialDesc box = floor;
  box.name = "box";
  box.baseColor = glm::vec4(0.7f, 0.45f, 0.3f, 1.0f);
  s.materials = {floor, box};
  MeshBuilder b{s};
  b.begin("floor", 0);
  float h = float(halfSize);
  // A grid of quads (not one): long thin triangles would make the rasterizer's and the ray
  // caster's silhouettes differ more than the surfaces under test.
  const int n = 8;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      b.quad({-h + 2 * h * i / n, 0, h - 2 * h * j / n}, {2 * h / n, 0, 0}, {0, 0, -2 * h / n});
  b.end();
  s.instances.push_back({b.meshIndex, glm::dmat4(1.0), true});
  b.begin("boxes", 1);
  b.box({-2.5f, 0, -1.5f}, {-1.0f, 1.5f, 0.0f});
  b.box({0.5f, 0, -3.0f}, {1.5f, 2.5f, -2.0f});
  b.box({1.5f, 0, 0.5f}, {2.5f, 0.8f, 1.5f});
  b.end();
  s.instances.push_back({b.meshIndex, glm::dmat4(1.0), true});
  s.sun.enabled = sun;
  s.sky.ambient = glm::vec3(0.05f);
  computeBounds(s);
  placeCamera(s, {0, 4, 9}, {0, 0.5, 0});
  return s;
}

void placeCamera(Scene& s, glm::dvec3 eye, glm::dvec3 target, double yfov, double znear, double zfar) {
  s.cameras = {lookAtCamera("stress", eye, target, yfov, znear, zfar)};
}

void translateScene(Scene& s, const glm::dvec3& offset) {
  glm::dmat4 t(1.0);
  t[3] = glm::dvec4(offset, 1.0);
  for (Instance& i : s.instances) i.worldFromObject = t * i.worldFromObject;
  for (CameraDesc& c : s.cameras) c.worldFromEye = t * c.worldFromEye;
  for (PointLightDesc& l : s.lights) l.center += offset;
  computeBounds(s);
}

}  // namespace gb::stress
