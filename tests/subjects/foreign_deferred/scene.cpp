// The Y-down scene, the orbiting camera and the uniform buffer's contents (see scene.h).
#include "scene.h"

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

namespace fd {

namespace {

constexpr float k_pi = 3.14159265358979f;

// The ground: the plane y = 0, its normal up, i.e. toward -Y.
mesh ground(float half) {
  mesh m;
  const glm::vec3 n(0, -1, 0);
  m.vertices = {{{-half, 0, -half}, n}, {{half, 0, -half}, n}, {{half, 0, half}, n}, {{-half, 0, half}, n}};
  m.indices = {0, 1, 2, 0, 2, 3};
  return m;
}

// The cube [-1, 1]^3 with one normal per face.
mesh cube() {
  mesh m;
  for (int axis = 0; axis < 3; ++axis)
    for (float sign : {-1.0f, 1.0f}) {
      glm::vec3 n(0), u(0), v(0);
      n[axis] = sign;
      u[(axis + 1) % 3] = 1;
      v[(axis + 2) % 3] = 1;
      const uint32_t base = uint32_t(m.vertices.size());
      for (glm::vec2 c : {glm::vec2(-1, -1), glm::vec2(1, -1), glm::vec2(1, 1), glm::vec2(-1, 1)})
        m.vertices.push_back({n + c.x * u + c.y * v, n});
      for (uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) m.indices.push_back(base + i);
    }
  return m;
}

// The unit sphere, latitude/longitude.
mesh sphere(uint32_t slices, uint32_t stacks) {
  mesh m;
  for (uint32_t j = 0; j <= stacks; ++j)
    for (uint32_t i = 0; i <= slices; ++i) {
      const float theta = k_pi * float(j) / float(stacks), phi = 2 * k_pi * float(i) / float(slices);
      const glm::vec3 p(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
      m.vertices.push_back({p, p});
    }
  for (uint32_t j = 0; j < stacks; ++j)
    for (uint32_t i = 0; i < slices; ++i) {
      const uint32_t a = j * (slices + 1) + i, b = a + slices + 1;
      for (uint32_t k : {a, b, a + 1, a + 1, b, b + 1}) m.indices.push_back(k);
    }
  return m;
}

glm::mat4 placed(glm::vec3 centre, glm::vec3 half_size, float turn_about_up = 0.0f) {
  glm::mat4 m = glm::translate(glm::mat4(1), centre);
  m = glm::rotate(m, turn_about_up, glm::vec3(0, -1, 0));
  return glm::scale(m, half_size);
}

}  // namespace

scene build_scene(uint32_t frame) {
  scene s;
  s.meshes = {ground(9.0f), cube(), sphere(32, 16)};
  // Every object rests on y = 0 and reaches up to negative y.
  s.draws = {
      {0, glm::mat4(1), {0.55f, 0.50f, 0.45f, 1}},
      {1, placed({-1.6f, -0.8f, 0.6f}, glm::vec3(0.8f), 0.3f), {0.80f, 0.25f, 0.20f, 1}},
      {1, placed({1.8f, -1.3f, -1.4f}, {0.5f, 1.3f, 0.5f}, 0.4f + 0.15f * float(frame)), {0.20f, 0.45f, 0.80f, 1}},
      {2, placed({0.6f, -1.0f, 2.0f}, glm::vec3(1.0f)), {0.85f, 0.80f, 0.30f, 1}},
      {2, placed({-2.6f, -0.6f, -2.2f}, glm::vec3(0.6f)), {0.30f, 0.75f, 0.35f, 1}},
  };
  return s;
}

camera build_camera(uint32_t frame, uint32_t width, uint32_t height, bool orthographic) {
  camera c;
  const float angle = 0.65f + 0.04f * float(frame);
  c.target = {0.0f, -0.9f, 0.0f};
  c.eye = c.target + glm::vec3(7.0f * std::cos(angle), -3.2f, 7.0f * std::sin(angle));  // above: y < 0
  c.up = {0.0f, -1.0f, 0.0f};
  c.orthographic = orthographic;
  c.view_from_world = glm::lookAtRH(c.eye, c.target, c.up);
  const float aspect = float(width) / float(height);
  if (orthographic) {
    const float h = k_ortho_half_height, w = h * aspect;
    c.clip_from_view = glm::orthoRH_ZO(-w, w, -h, h, k_near, k_far);
  } else {
    c.clip_from_view = glm::perspectiveRH_ZO(k_fovy, aspect, k_near, k_far);
  }
  c.clip_from_view[1][1] *= -1.0f;  // Vulkan clip space: +y is down the image
  return c;
}

frame_uniforms build_uniforms(const camera& c, uint32_t width, uint32_t height) {
  frame_uniforms u{};
  u.clip_from_view = c.clip_from_view;
  u.view_from_world = c.view_from_world;
  u.clip_from_world = c.clip_from_view * c.view_from_world;
  u.view_from_clip = glm::inverse(c.clip_from_view);
  const glm::mat3 rotate(c.view_from_world);
  u.sun_direction_view = glm::vec4(glm::normalize(rotate * glm::vec3(0.45f, -1.0f, 0.3f)), 0.0f);
  u.sun_color = {2.6f, 2.4f, 2.1f, 0};
  u.ambient = {0.18f, 0.20f, 0.25f, 0};
  u.depth_params = {k_near, k_far, 1.0f / k_far, c.orthographic ? 1.0f : 0.0f};
  const glm::vec4 lights[4] = {{-0.5f, -0.6f, 3.2f, 3.0f}, {2.8f, -0.8f, 0.6f, 2.5f}, {-3.0f, -1.8f, -0.8f, 4.0f},
                               {0.4f, -2.6f, -2.4f, 3.5f}};
  const glm::vec3 colors[4] = {{3.0f, 1.4f, 0.6f}, {0.5f, 1.6f, 3.0f}, {1.8f, 2.6f, 1.0f}, {2.4f, 0.8f, 2.2f}};
  for (int i = 0; i < 4; ++i) {
    u.light_position_view[i] = glm::vec4(glm::vec3(c.view_from_world * glm::vec4(glm::vec3(lights[i]), 1)), lights[i].w);
    u.light_color[i] = glm::vec4(colors[i], 0);
  }
  u.viewport = {float(width), float(height), 1.0f / float(width), 1.0f / float(height)};
  return u;
}

}  // namespace fd
