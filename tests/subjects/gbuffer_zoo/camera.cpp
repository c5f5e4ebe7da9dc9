// See camera.h. Projections are written out by hand (m[column][row]) so every convention is explicit:
// right-handed views look down -Z, y_down's left-handed one down +Z; "vulkan" clip space has y down
// (the projection negates y), world_tbn's "d3d" one y up with a negative-height viewport instead.
#include "camera.h"

#include <cmath>
#include <cstring>

#include <glm/gtc/matrix_transform.hpp>

#include "scene.h"

namespace zoo {

namespace {

struct Writer {
  Camera& cam;
  void raw(const char* name, const char* type, const float* v, size_t n) {
    cam.members.push_back({name, type, uint32_t(cam.block.size())});
    const auto* b = reinterpret_cast<const uint8_t*>(v);
    cam.block.insert(cam.block.end(), b, b + n * sizeof(float));
  }
  void mat(const char* name, const glm::mat4& m) {
    float f[16];
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) f[cam.row_major ? r * 4 + c : c * 4 + r] = m[c][r];
    raw(name, "mat4", f, 16);
  }
  void vec(const char* name, glm::vec4 v) { raw(name, "vec4", &v.x, 4); }
};

// Right-handed view (looks down -Z), depth 0..1; y_sign -1 puts clip y down (vulkan), +1 up (d3d).
glm::mat4 perspective_rh(float fovy, float aspect, float n, float f, float y_sign, bool reversed) {
  const float t = 1.0f / std::tan(fovy / 2);
  glm::mat4 m(0.0f);
  m[0][0] = t / aspect;
  m[1][1] = y_sign * t;
  m[2][3] = -1;
  m[2][2] = reversed ? n / (f - n) : f / (n - f);
  m[3][2] = reversed ? n * f / (f - n) : n * f / (n - f);
  return m;
}

// Left-handed view (looks down +Z), vulkan clip space (y down), depth 0..1.
glm::mat4 perspective_lh(float fovy, float aspect, float n, float f) {
  const float t = 1.0f / std::tan(fovy / 2);
  glm::mat4 m(0.0f);
  m[0][0] = t / aspect;
  m[1][1] = -t;
  m[2][3] = 1;
  m[2][2] = f / (f - n);
  m[3][2] = -n * f / (f - n);
  return m;
}

// The canonical Z-up right-handed world into y_down's Y-down left-handed one: (x, y, z) -> (x, -z, -y).
glm::mat4 y_down_from_canonical() {
  glm::mat4 m(0.0f);
  m[0][0] = 1, m[2][1] = -1, m[1][2] = -1, m[3][3] = 1;
  return m;
}

struct Planes {
  float near_plane, far_plane;
};

Planes planes(Mode m) {
  switch (m) {
    case Mode::world_tbn: return {0.25f, 80.0f};
    case Mode::forward: return {0.1f, 100.0f};
    case Mode::lighting_depth: return {0.2f, 120.0f};
    case Mode::stencil_dontcare: return {0.1f, 60.0f};
    case Mode::linear_depth: return {0.3f, 90.0f};
    case Mode::view_oct: return {0.1f, 200.0f};
    case Mode::y_down: return {0.15f, 75.0f};
  }
  return {0.1f, 100.0f};
}

// view_from_world and clip_from_view of frame k in mode m's world.
void matrices(Mode m, uint32_t frame, float aspect, Camera& c) {
  glm::vec3 eye, target;
  canonical_camera(frame, eye, target);
  c.to_world = m == Mode::y_down ? y_down_from_canonical() : glm::mat4(1);
  c.eye = glm::vec3(c.to_world * glm::vec4(eye, 1));
  c.target = glm::vec3(c.to_world * glm::vec4(target, 1));
  c.up = glm::mat3(c.to_world) * glm::vec3(0, 0, 1);
  c.fovy = m == Mode::y_down ? 0.95f : 0.9f;
  const Planes p = planes(m);
  c.near_plane = p.near_plane, c.far_plane = p.far_plane;
  if (m == Mode::y_down) {
    c.view_from_world = glm::lookAtLH(c.eye, c.target, c.up);
    c.clip_from_view = perspective_lh(c.fovy, aspect, c.near_plane, c.far_plane);
  } else {
    c.view_from_world = glm::lookAtRH(c.eye, c.target, c.up);
    const float y_sign = m == Mode::world_tbn ? 1.0f : -1.0f;
    c.clip_from_view = perspective_rh(c.fovy, aspect, c.near_plane, c.far_plane, y_sign, m == Mode::view_oct);
  }
  c.clip_from_world = c.clip_from_view * c.view_from_world;
}

void write_block(Mode m, uint32_t frame, float w, float h, Camera& c, const Camera& prev) {
  Writer wr{c};
  const glm::vec4 eye(c.eye, 1), viewport(w, h, 1 / w, 1 / h), range(c.near_plane, c.far_plane, 0, 0);
  switch (m) {
    case Mode::world_tbn:
      wr.mat("view_from_world", c.view_from_world), wr.mat("clip_from_view", c.clip_from_view);
      wr.mat("world_from_view", glm::inverse(c.view_from_world)), wr.mat("prev_clip_from_world", prev.clip_from_world);
      wr.vec("eye_world", eye), wr.vec("viewport", viewport);
      break;
    case Mode::forward:
      wr.mat("clip_from_world", c.clip_from_world), wr.mat("view_from_world", c.view_from_world);
      wr.mat("clip_from_view", c.clip_from_view), wr.vec("eye_world", eye), wr.vec("depth_range", range);
      break;
    case Mode::lighting_depth:
      wr.mat("view_from_world", c.view_from_world), wr.mat("clip_from_view", c.clip_from_view);
      wr.mat("clip_from_world", c.clip_from_world), wr.mat("world_from_clip", glm::inverse(c.clip_from_world));
      wr.mat("prev_clip_from_world", prev.clip_from_world), wr.vec("eye_world", eye);
      wr.vec("depth_range", range), wr.vec("viewport", viewport);
      break;
    case Mode::stencil_dontcare:
      wr.vec("frame_info", {float(frame), float(frame) / 60.0f, 0, 0});
      wr.mat("view_from_world", c.view_from_world), wr.mat("clip_from_view", c.clip_from_view);
      wr.mat("view_from_clip", glm::inverse(c.clip_from_view)), wr.mat("prev_view_from_world", prev.view_from_world);
      wr.vec("viewport", viewport);
      break;
    case Mode::linear_depth: {
      const float ty = std::tan(c.fovy / 2);
      wr.mat("world_from_view", glm::inverse(c.view_from_world)), wr.mat("view_from_world", c.view_from_world);
      wr.mat("clip_from_view", c.clip_from_view), wr.vec("proj_params", {ty * w / h, ty, c.near_plane, c.far_plane});
      wr.vec("viewport", viewport);
      break;
    }
    case Mode::view_oct:
      wr.mat("view_from_world[0]", c.view_from_world), wr.mat("view_from_world[1]", prev.view_from_world);
      wr.mat("clip_from_view", c.clip_from_view), wr.mat("view_from_clip", glm::inverse(c.clip_from_view));
      wr.mat("clip_from_world", c.clip_from_world), wr.vec("eye_world", eye), wr.vec("viewport", viewport);
      break;
    case Mode::y_down:
      wr.mat("clip_from_world", c.clip_from_world), wr.vec("eye_world", eye);
      wr.vec("frame_params", {w, h, float(frame), 0});
      break;
  }
}

}  // namespace

Camera make_camera(Mode mode, uint32_t frame, uint32_t width, uint32_t height) {
  const float aspect = float(width) / float(height);
  Camera c, prev;
  c.row_major = mode == Mode::y_down;
  matrices(mode, frame, aspect, c);
  matrices(mode, frame ? frame - 1 : 0, aspect, prev);
  write_block(mode, frame, float(width), float(height), c, prev);
  return c;
}

}  // namespace zoo
