// tiler_deferred's scene (scene.h): ground, two boxes, two spheres in a left-handed Z-up world; the camera
// orbits and the tall box turns with the frame index; nothing reads a clock or a random source.
#include "scene.h"

#include <cmath>

namespace td {

namespace {

mesh_range add_box(scene& s) {  // unit cube [-0.5, 0.5]^3, 24 vertices, face normals
  mesh_range r{uint32_t(s.indices.size()), 36, int32_t(s.vertices.size())};
  for (int axis = 0; axis < 3; ++axis)
    for (int sign = -1; sign <= 1; sign += 2) {
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      const uint32_t base = uint32_t(s.vertices.size()) - uint32_t(r.vertex_offset);
      for (int c = 0; c < 4; ++c) {
        vertex vx{};
        vx.position[axis] = 0.5f * float(sign);
        vx.position[u] = (c & 1) ? 0.5f : -0.5f;
        vx.position[v] = (c & 2) ? 0.5f : -0.5f;
        vx.normal[axis] = float(sign);
        s.vertices.push_back(vx);
      }
      for (uint32_t i : {0u, 1u, 3u, 0u, 3u, 2u}) s.indices.push_back(base + i);
    }
  return r;
}

mesh_range add_sphere(scene& s, int rings, int segments) {  // unit radius, Z poles
  mesh_range r{uint32_t(s.indices.size()), 0, int32_t(s.vertices.size())};
  const float pi = 3.14159265358979f;
  for (int i = 0; i <= rings; ++i)
    for (int j = 0; j <= segments; ++j) {
      const float theta = pi * float(i) / float(rings), phi = 2.0f * pi * float(j) / float(segments);
      const glm::vec3 n(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
      s.vertices.push_back({{n.x, n.y, n.z}, {n.x, n.y, n.z}});
    }
  for (int i = 0; i < rings; ++i)
    for (int j = 0; j < segments; ++j) {
      const uint32_t a = uint32_t(i * (segments + 1) + j), b = a + uint32_t(segments + 1);
      for (uint32_t k : {a, b, a + 1, a + 1, b, b + 1}) s.indices.push_back(k);
    }
  r.index_count = uint32_t(s.indices.size()) - r.first_index;
  return r;
}

glm::mat4 place(glm::vec3 at, glm::vec3 scale, float turn_about_z) {
  glm::mat4 m(1.0f);
  const float c = std::cos(turn_about_z), s = std::sin(turn_about_z);
  m[0] = glm::vec4(c * scale.x, s * scale.x, 0, 0);
  m[1] = glm::vec4(-s * scale.y, c * scale.y, 0, 0);
  m[2] = glm::vec4(0, 0, scale.z, 0);
  m[3] = glm::vec4(at, 1);
  return m;
}

}  // namespace

scene build_scene(uint32_t frame) {
  scene s;
  const mesh_range box = add_box(s), sphere = add_sphere(s, 16, 24);
  const float k = float(frame);
  s.objects = {
      {"ground", box, place({0, 0, -0.05f}, {14, 14, 0.1f}, 0), {0.55f, 0.52f, 0.48f, 0.9f}, 0.0f, 1, 1},
      {"crate", box, place({0.5f, -1.6f, 0.6f}, {1.2f, 1.2f, 1.2f}, 0.35f), {0.70f, 0.32f, 0.18f, 0.6f}, 0.0f, 1, 2},
      {"tower", box, place({1.8f, 1.4f, 1.25f}, {0.8f, 0.8f, 2.5f}, 0.2f * k), {0.25f, 0.45f, 0.75f, 0.35f}, 0.0f, 2, 3},
      {"ball", sphere, place({-0.8f, 0.4f, 0.75f}, glm::vec3(0.75f), 0), {0.85f, 0.85f, 0.82f, 0.2f}, 1.0f, 1, 4},
      {"marble", sphere, place({-1.8f, 2.0f * std::sin(0.5f * k), 0.35f}, glm::vec3(0.35f), 0),
       {0.20f, 0.70f, 0.30f, 0.5f}, 0.0f, 2, 5},
  };
  return s;
}

camera build_camera(uint32_t frame, uint32_t width, uint32_t height) {
  camera c;
  const float a = 0.35f + 0.05f * float(frame);
  c.target = {0.0f, 0.0f, 0.8f};
  c.eye = c.target + glm::vec3(-7.0f * std::cos(a), -7.0f * std::sin(a) * 0.6f, 3.2f);
  c.up = {0, 0, 1};
  c.fovy = 0.9f;
  c.near = 0.1f;
  // Left-handed view (D3D-like): +X right, +Y up, looking down +Z; det = +1 (world and view both left-handed).
  const glm::vec3 f = glm::normalize(c.target - c.eye);
  const glm::vec3 r = glm::normalize(glm::cross(c.up, f));
  const glm::vec3 u = glm::cross(f, r);
  glm::mat4 v(1.0f);  // glm m[column][row]
  for (int i = 0; i < 3; ++i) {
    v[i][0] = r[i];
    v[i][1] = u[i];
    v[i][2] = f[i];
  }
  v[3][0] = -glm::dot(r, c.eye);
  v[3][1] = -glm::dot(u, c.eye);
  v[3][2] = -glm::dot(f, c.eye);
  c.view_from_world = v;
  // Reverse-Z, infinite far: clip = (x f/aspect, -y f, near, z); depth = near / z_view (1 at near, 0 at infinity).
  const float t = 1.0f / std::tan(0.5f * c.fovy), aspect = float(width) / float(height);
  glm::mat4 p(0.0f);
  p[0][0] = t / aspect;
  p[1][1] = -t;
  p[3][2] = c.near;
  p[2][3] = 1.0f;
  c.clip_from_view = p;
  return c;
}

void store_row_major(const glm::mat4& m, float out[16]) {
  for (int row = 0; row < 4; ++row)
    for (int col = 0; col < 4; ++col) out[row * 4 + col] = m[col][row];
}

frame_block build_block(const camera& c, uint32_t frame, uint32_t width, uint32_t height, uint32_t mode) {
  frame_block b{};
  b.eye_world[0] = c.eye.x, b.eye_world[1] = c.eye.y, b.eye_world[2] = c.eye.z, b.eye_world[3] = 1.0f;
  const glm::mat4 clip_from_world = c.clip_from_view * c.view_from_world;
  store_row_major(c.view_from_world, b.view_from_world);
  store_row_major(c.clip_from_view, b.clip_from_view);
  store_row_major(clip_from_world, b.clip_from_world);
  store_row_major(glm::inverse(clip_from_world), b.world_from_clip);
  const glm::vec3 sun = glm::normalize(glm::vec3(-0.4f, 0.5f, 0.75f));
  const float sun4[4] = {sun.x, sun.y, sun.z, 0.0f}, sun_color[4] = {2.6f, 2.4f, 2.1f, 0.0f},
              ambient[4] = {0.10f, 0.12f, 0.16f, 0.0f};
  const float points[3][4] = {{-2.5f, -2.5f, 1.2f, 4.0f}, {2.5f, -0.5f, 0.6f, 3.0f}, {-1.0f, 3.0f, 1.8f, 5.0f}};
  const float colors[3][4] = {{1.6f, 0.6f, 0.2f, 0}, {0.3f, 0.9f, 1.5f, 0}, {1.2f, 1.2f, 0.9f, 0}};
  for (int i = 0; i < 4; ++i) {
    b.sun_toward[i] = sun4[i];
    b.sun_color[i] = sun_color[i];
    b.ambient[i] = ambient[i];
    for (int l = 0; l < 3; ++l) b.point_position[l][i] = points[l][i], b.point_color[l][i] = colors[l][i];
  }
  b.viewport[0] = float(width), b.viewport[1] = float(height);
  b.viewport[2] = 1.0f / float(width), b.viewport[3] = 1.0f / float(height);
  b.frame_info[0] = frame;
  b.frame_info[1] = 0xF0000000u | frame;
  b.frame_info[2] = mode;
  return b;
}

object_push build_push(const object& o) {
  object_push p{};
  store_row_major(o.world_from_object, p.world_from_object);
  for (int i = 0; i < 4; ++i) p.albedo_roughness[i] = o.albedo_roughness[i];
  p.material[0] = o.metalness;
  p.material[1] = float(o.flag);
  p.id = o.id;
  return p;
}

}  // namespace td
