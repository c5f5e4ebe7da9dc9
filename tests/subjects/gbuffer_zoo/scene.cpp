// See scene.h: procedural meshes with baked sizes (every model matrix is rigid, so mat3(model) maps
// normals), the object list of frame k and the lights.
#include "scene.h"

#include <cmath>
#include <cstring>

#include <glm/gtc/matrix_transform.hpp>

namespace zoo {

namespace {

constexpr float k_pi = 3.14159265358979f;

void put(float* dst, glm::vec3 v) { dst[0] = v.x, dst[1] = v.y, dst[2] = v.z; }

Vertex vertex(glm::vec3 p, glm::vec3 n, glm::vec3 t, glm::vec3 b, glm::vec2 uv) {
  Vertex v;
  put(v.pos, p), put(v.normal, n), put(v.tangent, t), put(v.bitangent, b);
  v.uv[0] = uv.x, v.uv[1] = uv.y;
  return v;
}

// A quad of 4 vertices p0..p3 (counter-clockwise seen from n), two triangles.
void add_quad(Geometry& g, const glm::vec3 p[4], glm::vec3 n, glm::vec3 t, glm::vec3 b, const glm::vec2 uv[4]) {
  const uint32_t base = uint32_t(g.vertices.size());
  for (int i = 0; i < 4; ++i) g.vertices.push_back(vertex(p[i], n, t, b, uv[i]));
  for (uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) g.indices.push_back(base + i);
}

void add_box(Geometry& g, glm::vec3 half) {
  const glm::vec3 axes[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const glm::vec2 uv[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  for (int a = 0; a < 3; ++a)
    for (float s : {1.0f, -1.0f}) {
      const glm::vec3 n = axes[a] * s, t = axes[(a + 1) % 3] * s, b = glm::cross(n, t);
      const float hn = half[a], ht = half[(a + 1) % 3], hb = half[(a + 2) % 3];
      const glm::vec3 c = n * hn;
      const glm::vec3 p[4] = {c - t * ht - b * hb, c + t * ht - b * hb, c + t * ht + b * hb, c - t * ht + b * hb};
      add_quad(g, p, n, t, b, uv);
    }
}

// u = longitude / 2pi, v = 1 - polar angle / pi; tangent east, bitangent north (t x b = n).
void add_sphere(Geometry& g, float radius, int segments, int rings) {
  const uint32_t base = uint32_t(g.vertices.size());
  for (int r = 0; r <= rings; ++r)
    for (int s = 0; s <= segments; ++s) {
      const float theta = k_pi * float(r) / float(rings), phi = 2 * k_pi * float(s) / float(segments);
      const glm::vec3 n(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
      const glm::vec3 t(-std::sin(phi), std::cos(phi), 0);
      const glm::vec3 b = glm::cross(n, t);
      g.vertices.push_back(vertex(n * radius, n, t, b, {float(s) / float(segments), 1 - float(r) / float(rings)}));
    }
  for (int r = 0; r < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      const uint32_t a = base + uint32_t(r * (segments + 1) + s), c = a + uint32_t(segments + 1);
      for (uint32_t i : {a, c, a + 1, a + 1, c, c + 1}) g.indices.push_back(i);
    }
}

void add_flat(Geometry& g, glm::vec2 lo, glm::vec2 hi, float z, float uv_per_metre) {
  const glm::vec3 p[4] = {{lo.x, lo.y, z}, {hi.x, lo.y, z}, {hi.x, hi.y, z}, {lo.x, hi.y, z}};
  glm::vec2 uv[4];
  for (int i = 0; i < 4; ++i)
    uv[i] = uv_per_metre > 0 ? glm::vec2(p[i]) * uv_per_metre : glm::vec2(i == 1 || i == 2, i >= 2);
  add_quad(g, p, {0, 0, 1}, {1, 0, 0}, {0, 1, 0}, uv);
}

void store(float* dst, const glm::mat4& m, bool row_major) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) dst[row_major ? r * 4 + c : c * 4 + r] = m[c][r];
}

glm::mat4 placed(glm::vec3 at, float turn) {
  return glm::rotate(glm::translate(glm::mat4(1), at), turn, glm::vec3(0, 0, 1));
}

}  // namespace

Geometry build_geometry() {
  Geometry g;
  auto begin = [&](MeshId id) {
    g.meshes[id].first_index = uint32_t(g.indices.size());
    g.meshes[id].vertex_offset = 0;
  };
  auto end = [&](MeshId id) { g.meshes[id].index_count = uint32_t(g.indices.size()) - g.meshes[id].first_index; };
  begin(mesh_floor), add_flat(g, {-200, -200}, {200, 200}, 0, 1), end(mesh_floor);
  begin(mesh_cube), add_box(g, {0.8f, 0.8f, 0.8f}), end(mesh_cube);
  begin(mesh_tall_box), add_box(g, {0.45f, 0.45f, 1.5f}), end(mesh_tall_box);
  begin(mesh_flat_box), add_box(g, {1.1f, 0.7f, 0.3f}), end(mesh_flat_box);
  begin(mesh_big_sphere), add_sphere(g, 1.0f, 20, 10), end(mesh_big_sphere);
  begin(mesh_small_sphere), add_sphere(g, 0.6f, 20, 10), end(mesh_small_sphere);
  begin(mesh_marker), add_sphere(g, 0.12f, 10, 6), end(mesh_marker);
  begin(mesh_decal), add_flat(g, {-2.6f, -1.35f}, {-1.0f, 0.25f}, 0.004f, 0), end(mesh_decal);
  return g;
}

std::vector<SceneObject> scene_objects(uint32_t frame) {
  const float k = float(frame);
  const uint32_t box = k_stencil_box, ball = k_stencil_sphere;
  return {
      {mesh_floor, glm::mat4(1), {0.60f, 0.57f, 0.52f}, 0.85f, 0, 0.25f, 1.0f, 1, k_stencil_floor, false},
      {mesh_cube, placed({-1.3f, 1.15f, 0.8f}, 0.5f), {0.75f, 0.20f, 0.12f}, 0.5f, 0, 0.6f, 3.0f, 2, box, false},
      {mesh_tall_box, placed({1.9f, -0.9f, 1.5f}, 0.3f + 0.2f * k), {0.15f, 0.30f, 0.80f}, 0.3f, 0, 0, 1.0f, 0, box,
       false},
      {mesh_flat_box, placed({0.25f, -3.05f, 0.3f}, -0.3f), {0.85f, 0.70f, 0.20f}, 0.6f, 0, 0.3f, 4.0f, 1, box, false},
      {mesh_big_sphere, placed({1.7f, 1.9f, 1.0f}, 0), {0.20f, 0.70f, 0.30f}, 0.4f, 0, 0.8f, 8.0f, 3, ball, false},
      {mesh_small_sphere, placed({-0.45f, -1.0f, 0.6f}, 0), {0.90f, 0.90f, 0.92f}, 0.15f, 1, 0, 1.0f, 0,
       ball | k_stencil_metal, false},
      {mesh_decal, glm::mat4(1), {0.90f, 0.15f, 0.50f}, 0.5f, 0, 0, 1.0f, 0, 0, true},
  };
}

std::vector<ObjectGpu> pack_objects(uint32_t frame, const glm::mat4& to_world, bool row_major) {
  const std::vector<SceneObject> now = scene_objects(frame), before = scene_objects(frame ? frame - 1 : 0);
  std::vector<ObjectGpu> out(now.size());
  for (size_t i = 0; i < now.size(); ++i) {
    const SceneObject& o = now[i];
    ObjectGpu& g = out[i];
    std::memset(&g, 0, sizeof g);
    store(g.world_from_object, to_world * o.model, row_major);
    store(g.prev_world_from_object, to_world * before[i].model, row_major);
    put(g.albedo, o.albedo), g.albedo[3] = 1;
    g.material[0] = o.roughness, g.material[1] = o.metallic, g.material[2] = o.bump, g.material[3] = o.uv_scale;
    g.info[0] = o.pattern, g.info[1] = o.stencil, g.info[2] = uint32_t(i + 1), g.info[3] = o.decal ? 1 : 0;
  }
  return out;
}

LightsGpu pack_lights(const glm::mat4& to_world) {
  LightsGpu l;
  std::memset(&l, 0, sizeof l);
  put(l.sun_dir, glm::normalize(glm::mat3(to_world) * glm::vec3(-0.45f, -0.35f, 0.82f)));
  put(l.sun_color, {1.5f, 1.4f, 1.25f});
  put(l.ambient, {0.05f, 0.06f, 0.08f});
  const glm::vec4 points[4] = {{-2.6f, -1.2f, 1.9f, 6}, {2.4f, 1.0f, 2.3f, 6}, {0.4f, -3.0f, 1.3f, 4}, {-1.2f, 3.2f, 2.6f, 5}};
  const glm::vec3 colors[4] = {{3.0f, 1.8f, 0.9f}, {0.8f, 1.4f, 3.0f}, {1.0f, 2.6f, 1.2f}, {2.4f, 0.8f, 2.2f}};
  for (int i = 0; i < 4; ++i) {
    put(l.point_pos[i], glm::vec3(to_world * glm::vec4(glm::vec3(points[i]), 1)));
    l.point_pos[i][3] = points[i].w;
    put(l.point_color[i], colors[i]);
  }
  return l;
}

void canonical_camera(uint32_t frame, glm::vec3& eye, glm::vec3& target) {
  const float azimuth = 3.95f + 0.03f * float(frame), elevation = 0.22f, distance = 6.5f;
  target = {0.3f, 0.2f, 0.8f};
  eye = target + distance * glm::vec3(std::cos(elevation) * std::cos(azimuth), std::cos(elevation) * std::sin(azimuth),
                                      std::sin(elevation));
}

}  // namespace zoo
