// The zoo's scene, authored once in a Z-up, right-handed "canonical" world (metres): a huge floor
// quad, three boxes, two spheres, a decal quad and four point lights. Each mode maps it into its own
// world (y_down mirrors it into a Y-down left-handed one); frame k turns the tall box.
#pragma once
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace zoo {

struct Vertex {  // 56 bytes, binding 0
  float pos[3], normal[3], tangent[3], bitangent[3], uv[2];
};

struct MeshRange {
  uint32_t first_index = 0, index_count = 0;
  int32_t vertex_offset = 0;
};

enum MeshId { mesh_floor, mesh_cube, mesh_tall_box, mesh_flat_box, mesh_big_sphere, mesh_small_sphere, mesh_marker,
              mesh_decal, mesh_count };

struct Geometry {
  std::vector<Vertex> vertices;
  std::vector<uint32_t> indices;
  MeshRange meshes[mesh_count];
};

// One entry of the objects storage buffer (std430, 176 bytes; README.md).
struct ObjectGpu {
  float world_from_object[16];
  float prev_world_from_object[16];
  float albedo[4];    // linear rgb, a = 1
  float material[4];  // roughness, metallic, bump strength, uv scale
  uint32_t info[4];   // pattern (0 plain, 1 checker, 2 noise, 3 stripes), stencil bits, id, kind (0 scene, 1 decal)
};
static_assert(sizeof(ObjectGpu) == 176, "std430 object layout");

// The lights uniform buffer (set 0 binding 2 of the lighting passes, std140, 176 bytes).
struct LightsGpu {
  float sun_dir[4];  // toward the sun, unit, mode's world space
  float sun_color[4];
  float ambient[4];
  float point_pos[4][4];  // xyz mode's world space, w radius
  float point_color[4][4];
};
static_assert(sizeof(LightsGpu) == 176, "std140 lights layout");

struct SceneObject {
  MeshId mesh;
  glm::mat4 model;  // canonical world from object
  glm::vec3 albedo;
  float roughness, metallic, bump, uv_scale;
  uint32_t pattern, stencil;
  bool decal;
};

constexpr uint32_t k_stencil_floor = 0x01, k_stencil_box = 0x02, k_stencil_sphere = 0x04, k_stencil_metal = 0x80;

Geometry build_geometry();
std::vector<SceneObject> scene_objects(uint32_t frame);
// The SSBO contents: `to_world` maps the canonical world into the mode's; row_major stores each
// matrix transposed (m[row][col]) for layout(row_major) blocks.
std::vector<ObjectGpu> pack_objects(uint32_t frame, const glm::mat4& to_world, bool row_major);
LightsGpu pack_lights(const glm::mat4& to_world);
// The canonical camera of frame k: eye, target, up = +Z.
void canonical_camera(uint32_t frame, glm::vec3& eye, glm::vec3& target);

}  // namespace zoo
