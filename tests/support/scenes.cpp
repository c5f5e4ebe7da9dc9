// Small scenes for tests, built in code (see scenes.h).
#include "tests/support/scenes.h"

#include "renderer/core/camera.h"
#include "renderer/scene/mesh_builder.h"

namespace gb {

Scene floorScene(double halfSize, float specular) {
  Scene s;
  s.source = "test:floor";
  MaterialDesc m;
  m.name = "grey";
  m.baseColor = glm::vec4(0.5f, 0.5f, 0.5f, 1.0f);
  m.specular = specular;
  s.materials.push_back(m);
  MeshBuilder b{s};
  b.begin("floor", 0);
  float h = float(halfSize);
  b.quad({-h, 0, h}, {2 * h, 0, 0}, {0, 0, -2 * h});
  b.end();
  s.instances.push_back({b.meshIndex, glm::dmat4(1.0), true});
  s.sun.enabled = false;
  s.sky.ambient = glm::vec3(0.0f);
  computeBounds(s);
  setCamera(s, {0, 5, 5}, {0, 0, 0});
  return s;
}

void addBox(Scene& s, glm::vec3 lo, glm::vec3 hi, int material) {
  MeshBuilder b{s};
  b.begin("box", material);
  b.box(lo, hi);
  b.end();
  s.instances.push_back({b.meshIndex, glm::dmat4(1.0), true});
  computeBounds(s);
}

void setCamera(Scene& s, glm::dvec3 eye, glm::dvec3 target, double yfov, double znear, double zfar) {
  s.cameras = {lookAtCamera("test", eye, target, yfov, znear, zfar)};
}

std::string base64(const std::string& bytes) {
  static const char* t = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < bytes.size(); i += 3) {
    uint32_t v = uint32_t(uint8_t(bytes[i])) << 16;
    if (i + 1 < bytes.size()) v |= uint32_t(uint8_t(bytes[i + 1])) << 8;
    if (i + 2 < bytes.size()) v |= uint8_t(bytes[i + 2]);
    out += t[v >> 18 & 63];
    out += t[v >> 12 & 63];
    out += i + 1 < bytes.size() ? t[v >> 6 & 63] : '=';
    out += i + 2 < bytes.size() ? t[v & 63] : '=';
  }
  return out;
}

}  // namespace gb
