// tiler_deferred's scene and camera: a left-handed, Z-up world (X forward, Y right, Z up), meshes built in
// code, a reverse-Z infinite projection, and the frame uniform block with row-major matrices (README.md).
#pragma once
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace td {

struct vertex {
  float position[3];
  float normal[3];
};

struct mesh_range {
  uint32_t first_index = 0, index_count = 0;
  int32_t vertex_offset = 0;
};

struct object {
  const char* name;
  mesh_range mesh;
  glm::mat4 world_from_object;  // glm: column-major in memory
  glm::vec4 albedo_roughness;
  float metalness;
  uint32_t flag;  // 1 static, 2 animated (normal.a)
  uint32_t id;
};

struct scene {
  std::vector<vertex> vertices;
  std::vector<uint32_t> indices;
  std::vector<object> objects;
};

// The same meshes every frame; object transforms move with frame k.
scene build_scene(uint32_t frame);

struct camera {
  glm::vec3 eye, target, up;
  float fovy, near;
  glm::mat4 view_from_world, clip_from_view;  // glm matrices (column vectors)
};
camera build_camera(uint32_t frame, uint32_t width, uint32_t height);

// The frame uniform block (set 0, binding 0, a UNIFORM_BUFFER_DYNAMIC; std140; matrices ROW-MAJOR:
// element [row][column] at float index row * 4 + column). 448 bytes.
struct frame_block {
  float eye_world[4];           //   0
  float view_from_world[16];    //  16
  float clip_from_view[16];     //  80
  float clip_from_world[16];    // 144
  float world_from_clip[16];    // 208
  float sun_toward[4];          // 272: unit vector toward the sun, world
  float sun_color[4];           // 288
  float ambient[4];             // 304
  float point_position[3][4];   // 320: xyz world, w radius
  float point_color[3][4];      // 368
  float viewport[4];            // 416: width, height, 1/width, 1/height
  uint32_t frame_info[4];       // 432: k, id clear value, mode (0 subpass, 1 msaa), 0
};
static_assert(sizeof(frame_block) == 448);

frame_block build_block(const camera& c, uint32_t frame, uint32_t width, uint32_t height, uint32_t mode);
void store_row_major(const glm::mat4& m, float out[16]);

// Per-draw push constants (vertex + fragment, std430, 112 bytes).
struct object_push {
  float world_from_object[16];  //  0: row-major
  float albedo_roughness[4];    // 64
  float material[4];            // 80: metalness, flag, 0, 0
  uint32_t id;                  // 96
  uint32_t pad[3];
};
static_assert(sizeof(object_push) == 112);
object_push build_push(const object& o);

}  // namespace td
