// foreign_deferred's scene, authored in a Y-DOWN world: -Y is up, the ground is the plane y = 0 and
// everything stands on it toward -Y. The camera's view matrix is built with up = (0, -1, 0). Frame k
// moves the camera along its orbit and turns one box, so frames differ and frame k is reproducible.
#pragma once
#include <glm/glm.hpp>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace fd {

// The camera uniform buffer (set 0, binding 0) as GLSL std140 lays it out: the projection BEFORE
// the view matrix. Matrices column-major (glm's and GLSL's storage), Vulkan clip space (y down,
// depth 0..1, standard: near -> 0, far -> 1).
struct frame_uniforms {
  glm::mat4 clip_from_view;            // 0: the projection
  glm::mat4 view_from_world;           // 64: the view matrix
  glm::mat4 clip_from_world;           // 128: projection * view (not used by the shaders)
  glm::mat4 view_from_clip;            // 192: inverse projection (not used by the shaders)
  glm::vec4 sun_direction_view;        // 256: unit vector toward the sun, view space
  glm::vec4 sun_color;                 // 272
  glm::vec4 ambient;                   // 288
  glm::vec4 depth_params;              // 304: near, far, 1 / far, 1 when orthographic else 0
  glm::vec4 light_position_view[4];    // 320: xyz view space, w the radius
  glm::vec4 light_color[4];            // 384
  glm::vec4 viewport;                  // 448: width, height, 1 / width, 1 / height
};
static_assert(offsetof(frame_uniforms, view_from_world) == 64);
static_assert(offsetof(frame_uniforms, depth_params) == 304);
static_assert(offsetof(frame_uniforms, viewport) == 448);
static_assert(sizeof(frame_uniforms) == 464);

constexpr float k_near = 0.25f;
constexpr float k_far = 32.0f;  // a power of two: w = eye depth * (1 / far) is exact in fp32
constexpr float k_fovy = 0.87f;           // perspective: vertical field of view, radians
constexpr float k_ortho_half_height = 3.4f;  // orthographic: half the view's height, world units

struct vertex {
  glm::vec3 position;
  glm::vec3 normal;
};

struct mesh {
  std::vector<vertex> vertices;
  std::vector<uint32_t> indices;
};

struct draw {
  uint32_t mesh = 0;               // index into scene::meshes
  glm::mat4 world_from_object{1};  // rigid transforms and scales along the object's axes only
  glm::vec4 albedo{1};             // linear
};

struct camera {
  glm::vec3 eye{0}, target{0}, up{0, -1, 0};
  glm::mat4 view_from_world{1}, clip_from_view{1};
  bool orthographic = false;
};

struct scene {
  std::vector<mesh> meshes;
  std::vector<draw> draws;
};

scene build_scene(uint32_t frame);
camera build_camera(uint32_t frame, uint32_t width, uint32_t height, bool orthographic);
frame_uniforms build_uniforms(const camera& c, uint32_t width, uint32_t height);

}  // namespace fd
