// Procedural mesh generation. Every face is counter-clockwise seen from its front (glTF's rule).
#include "renderer/scene/mesh_builder.h"

#include <cmath>

#include "renderer/core/assert.h"

namespace gb {

static constexpr float kPi = 3.14159265358979f;

uint32_t MeshBuilder::begin(const char* name, int material) {
  Mesh m;
  m.name = name;
  m.material = material;
  m.firstIndex = uint32_t(scene.indices.size());
  m.firstVertex = uint32_t(scene.vertices.size());
  scene.meshes.push_back(m);
  meshIndex = uint32_t(scene.meshes.size() - 1);
  return meshIndex;
}

void MeshBuilder::end() {
  Mesh& m = scene.meshes[meshIndex];
  m.indexCount = uint32_t(scene.indices.size()) - m.firstIndex;
  m.vertexCount = uint32_t(scene.vertices.size()) - m.firstVertex;
}

uint32_t MeshBuilder::vertex(const glm::vec3& p, const glm::vec3& n, const glm::vec2& uv) {
  Vertex v;
  v.position = p;
  v.normal = glm::normalize(n);
  v.uv0 = v.uv1 = uv;
  // Any tangent perpendicular to n (the built-in scene has no normal maps).
  glm::vec3 t = std::abs(v.normal.y) < 0.9f ? glm::cross(glm::vec3(0, 1, 0), v.normal) : glm::vec3(1, 0, 0);
  v.tangent = glm::vec4(glm::normalize(t), 1.0f);
  scene.vertices.push_back(v);
  return uint32_t(scene.vertices.size()) - 1 - scene.meshes[meshIndex].firstVertex;
}

void MeshBuilder::triangle(uint32_t a, uint32_t b, uint32_t c) {
  scene.indices.push_back(a);
  scene.indices.push_back(b);
  scene.indices.push_back(c);
}

void MeshBuilder::quad(const glm::vec3& o, const glm::vec3& u, const glm::vec3& v, glm::vec2 uvScale) {
  glm::vec3 n = glm::normalize(glm::cross(u, v));
  uint32_t a = vertex(o, n, {0, uvScale.y});
  uint32_t b = vertex(o + u, n, {uvScale.x, uvScale.y});
  uint32_t c = vertex(o + u + v, n, {uvScale.x, 0});
  uint32_t d = vertex(o + v, n, {0, 0});
  triangle(a, b, c);
  triangle(a, c, d);
}

void MeshBuilder::box(const glm::vec3& lo, const glm::vec3& hi, float uvPerUnit) {
  glm::vec3 s = hi - lo;
  glm::vec3 X(s.x, 0, 0), Y(0, s.y, 0), Z(0, 0, s.z);
  auto uv = [&](float a, float b) { return glm::vec2(a, b) * uvPerUnit; };
  quad(lo + Z, X, Y, uv(s.x, s.y));                  // +Z face
  quad(lo + X, -X, Y, uv(s.x, s.y));                 // -Z face (origin at +X corner)
  quad(lo + X + Z, -Z, Y, uv(s.z, s.y));             // +X face
  quad(lo, Z, Y, uv(s.z, s.y));                      // -X face
  quad(lo + Y + Z, X, -Z, uv(s.x, s.z));             // +Y face
  quad(lo, X, Z, uv(s.x, s.z));                      // -Y face
}

void MeshBuilder::cylinder(const glm::vec3& base, float r, float h, int segments, bool caps) {
  uint32_t first = 0;
  for (int i = 0; i <= segments; ++i) {
    float a = 2.0f * kPi * float(i) / float(segments);
    glm::vec3 n(std::cos(a), 0.0f, -std::sin(a));
    uint32_t v0 = vertex(base + n * r, n, {float(i) / segments * 2.0f, h});
    vertex(base + n * r + glm::vec3(0, h, 0), n, {float(i) / segments * 2.0f, 0.0f});
    if (i == 0) first = v0;
  }
  for (int i = 0; i < segments; ++i) {
    uint32_t a = first + 2 * i, b = a + 2;
    triangle(a, b, b + 1);
    triangle(a, b + 1, a + 1);
  }
  if (!caps) return;
  for (int top = 0; top < 2; ++top) {
    glm::vec3 n(0, top ? 1.0f : -1.0f, 0);
    glm::vec3 c = base + glm::vec3(0, top ? h : 0.0f, 0);
    uint32_t centre = vertex(c, n, {0.5f, 0.5f});
    uint32_t ring = 0;
    for (int i = 0; i <= segments; ++i) {
      float a = 2.0f * kPi * float(i) / float(segments);
      uint32_t v = vertex(c + glm::vec3(std::cos(a), 0, -std::sin(a)) * r, n,
                          {0.5f + 0.5f * std::cos(a), 0.5f + 0.5f * std::sin(a)});
      if (i == 0) ring = v;
    }
    for (int i = 0; i < segments; ++i) {
      if (top)
        triangle(centre, ring + i, ring + i + 1);
      else
        triangle(centre, ring + i + 1, ring + i);
    }
  }
}

void MeshBuilder::sphere(const glm::vec3& centre, float r, int segments, int rings) {
  uint32_t first = 0;
  for (int j = 0; j <= rings; ++j) {
    float theta = kPi * float(j) / float(rings);
    for (int i = 0; i <= segments; ++i) {
      float phi = 2.0f * kPi * float(i) / float(segments);
      glm::vec3 n(std::sin(theta) * std::cos(phi), std::cos(theta), -std::sin(theta) * std::sin(phi));
      uint32_t v = vertex(centre + n * r, n, {float(i) / segments, float(j) / rings});
      if (i == 0 && j == 0) first = v;
    }
  }
  uint32_t stride = uint32_t(segments + 1);
  for (int j = 0; j < rings; ++j) {
    for (int i = 0; i < segments; ++i) {
      uint32_t a = first + j * stride + i, b = a + stride;
      if (j != 0) triangle(a, b, a + 1);
      if (j != rings - 1) triangle(a + 1, b, b + 1);
    }
  }
}

void MeshBuilder::torus(const glm::vec3& centre, float R, float r, int segments, int sides) {
  uint32_t first = 0;
  for (int i = 0; i <= segments; ++i) {
    float u = 2.0f * kPi * float(i) / float(segments);
    glm::vec3 dir(std::cos(u), 0.0f, -std::sin(u));
    for (int j = 0; j <= sides; ++j) {
      float v = 2.0f * kPi * float(j) / float(sides);
      glm::vec3 n = dir * std::cos(v) + glm::vec3(0, std::sin(v), 0);
      uint32_t idx = vertex(centre + dir * R + n * r, n, {float(i) / segments * 4.0f, float(j) / sides});
      if (i == 0 && j == 0) first = idx;
    }
  }
  uint32_t stride = uint32_t(sides + 1);
  for (int i = 0; i < segments; ++i) {
    for (int j = 0; j < sides; ++j) {
      uint32_t a = first + i * stride + j, b = a + stride;
      triangle(a, b, b + 1);
      triangle(a, b + 1, a + 1);
    }
  }
}

const Icosahedron& icosahedron() {
  static const Icosahedron ico = [] {
    Icosahedron m{};
    const float t = (1.0f + std::sqrt(5.0f)) * 0.5f;
    const glm::vec3 v[12] = {{-1, t, 0}, {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t},  {0, 1, t},
                             {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
    for (int i = 0; i < 12; ++i) m.vertices[i] = glm::normalize(v[i]);
    const uint16_t f[60] = {0, 11, 5, 0, 5,  1,  0, 1, 7, 0, 7,  10, 0, 10, 11, 1, 5, 9, 5, 11,
                            4, 11, 10, 2, 10, 7, 6, 7, 1, 8, 3, 9, 4, 3, 4, 2, 3, 2, 6, 3,
                            6, 8,  3, 8, 9,  4, 9, 5, 2, 4, 11, 6, 2, 10, 8, 6, 7, 9, 8, 1};
    for (int i = 0; i < 60; ++i) m.indices[i] = f[i];
    // Check the winding once: every face's normal must point away from the centre.
    for (int i = 0; i < 60; i += 3) {
      glm::vec3 a = m.vertices[f[i]], b = m.vertices[f[i + 1]], c = m.vertices[f[i + 2]];
      GB_ASSERT(glm::dot(glm::cross(b - a, c - a), a + b + c) > 0.0f);
    }
    return m;
  }();
  return ico;
}

}  // namespace gb
