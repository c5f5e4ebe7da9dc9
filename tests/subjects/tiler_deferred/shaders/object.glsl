// tiler_deferred: per-draw push constants (scene.h object_push), std430, row-major matrix.
layout(push_constant, row_major, std430) uniform object_data {
  mat4 world_from_object;  //  0
  vec4 albedo_roughness;   // 64
  vec4 material;           // 80: metalness, flag (1 static, 2 animated)
  uint id;                 // 96
} object;
