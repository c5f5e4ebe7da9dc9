// The camera uniform block (set 0 binding 0) of each mode, selected by -DZOO_MODE=n, with
// zoo_clip(world position) and, where the mode has a view matrix, zoo_view(): view_from_world.
// Offsets are std140 and listed in README.md; camera.cpp writes the same members in the same order.
#if ZOO_MODE == 1  // world_tbn: view first, d3d-style clip (y up) drawn through a negative viewport
layout(set = 0, binding = 0, std140) uniform Camera {
  mat4 view_from_world, clip_from_view, world_from_view, prev_clip_from_world;
  vec4 eye_world, viewport;
} cam;
vec4 zoo_clip(vec3 p) { return cam.clip_from_view * (cam.view_from_world * vec4(p, 1)); }
mat4 zoo_view() { return cam.view_from_world; }
#elif ZOO_MODE == 2  // forward
layout(set = 0, binding = 0, std140) uniform Camera {
  mat4 clip_from_world, view_from_world, clip_from_view;
  vec4 eye_world, depth_range;
} cam;
vec4 zoo_clip(vec3 p) { return cam.clip_from_world * vec4(p, 1); }
mat4 zoo_view() { return cam.view_from_world; }
#elif ZOO_MODE == 3  // lighting_depth
layout(set = 0, binding = 0, std140) uniform Camera {
  mat4 view_from_world, clip_from_view, clip_from_world, world_from_clip, prev_clip_from_world;
  vec4 eye_world, depth_range, viewport;
} cam;
vec4 zoo_clip(vec3 p) { return cam.clip_from_world * vec4(p, 1); }
mat4 zoo_view() { return cam.view_from_world; }
#elif ZOO_MODE == 4  // stencil_dontcare: a vec4 before the matrices
layout(set = 0, binding = 0, std140) uniform Camera {
  vec4 frame_info;
  mat4 view_from_world, clip_from_view, view_from_clip, prev_view_from_world;
  vec4 viewport;
} cam;
vec4 zoo_clip(vec3 p) { return cam.clip_from_view * (cam.view_from_world * vec4(p, 1)); }
mat4 zoo_view() { return cam.view_from_world; }
#elif ZOO_MODE == 5  // linear_depth: the camera's transform first
layout(set = 0, binding = 0, std140) uniform Camera {
  mat4 world_from_view, view_from_world, clip_from_view;
  vec4 proj_params;  // tan(fov_x / 2), tan(fov_y / 2), near, far
  vec4 viewport;
} cam;
vec4 zoo_clip(vec3 p) { return cam.clip_from_view * (cam.view_from_world * vec4(p, 1)); }
mat4 zoo_view() { return cam.view_from_world; }
#elif ZOO_MODE == 6  // view_oct: [0] this frame's view, [1] the previous frame's; reversed Z
layout(set = 0, binding = 0, std140) uniform Camera {
  mat4 view_from_world[2];
  mat4 clip_from_view, view_from_clip, clip_from_world;
  vec4 eye_world, viewport;
} cam;
vec4 zoo_clip(vec3 p) { return cam.clip_from_view * (cam.view_from_world[0] * vec4(p, 1)); }
mat4 zoo_view() { return cam.view_from_world[0]; }
#elif ZOO_MODE == 7  // y_down: row-major, only the combined matrix and the eye
layout(set = 0, binding = 0, std140, row_major) uniform Camera {
  mat4 clip_from_world;
  vec4 eye_world;
  vec4 frame_params;  // width, height, frame index, 0
} cam;
vec4 zoo_clip(vec3 p) { return cam.clip_from_world * vec4(p, 1); }
#else
#error ZOO_MODE must be 1..7
#endif

// Per-object data (binding 1, std430, 176 bytes an object); y_down stores its matrices row-major.
struct ZooObject {
  mat4 world_from_object, prev_world_from_object;
  vec4 albedo;    // linear rgb
  vec4 material;  // roughness, metallic, bump strength, uv scale
  uvec4 info;     // pattern, stencil bits, id, kind
};
#if ZOO_MODE == 7
layout(set = 0, binding = 1, std430, row_major) readonly buffer Objects { ZooObject objects[]; };
#else
layout(set = 0, binding = 1, std430) readonly buffer Objects { ZooObject objects[]; };
#endif

// The lights (binding 2, std140), in the mode's world space.
layout(set = 0, binding = 2, std140) uniform Lights {
  vec4 sun_dir, sun_color, ambient;
  vec4 point_pos[4];  // xyz position, w radius
  vec4 point_color[4];
} lights;
