// Procedural meshes for the built-in scene and the light volumes: boxes, cylinders, spheres,
// tori, cards, and the icosahedron that bounds a point light.
#pragma once
#include <glm/glm.hpp>

#include "renderer/core/light_rect.h"  // kIcosahedronInradius
#include "renderer/scene/scene.h"

namespace gb {

// Appends triangles to a Scene as one Mesh per call (object space = the given placement).
struct MeshBuilder {
  Scene& scene;
  uint32_t begin(const char* name, int material);  // starts a mesh, returns its index
  void end();
  uint32_t vertex(const glm::vec3& p, const glm::vec3& n, const glm::vec2& uv);
  void triangle(uint32_t a, uint32_t b, uint32_t c);
  void quad(const glm::vec3& o, const glm::vec3& u, const glm::vec3& v, glm::vec2 uvScale = {1, 1});
  void box(const glm::vec3& lo, const glm::vec3& hi, float uvPerUnit = 1.0f);
  void cylinder(const glm::vec3& base, float radius, float height, int segments, bool caps = true);
  void sphere(const glm::vec3& centre, float radius, int segments, int rings);
  void torus(const glm::vec3& centre, float majorRadius, float minorRadius, int segments, int sides);
  uint32_t meshIndex = 0;
};

// Unit icosahedron (circumradius 1): 12 vertices, 20 faces, counter-clockwise seen from outside.
struct Icosahedron {
  glm::vec3 vertices[12];
  uint16_t indices[60];
};
const Icosahedron& icosahedron();

}  // namespace gb
