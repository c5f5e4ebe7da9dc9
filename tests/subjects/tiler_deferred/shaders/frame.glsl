// tiler_deferred: the frame uniform block (scene.h frame_block), std140, ROW-MAJOR matrices, a dynamic
// uniform buffer at set 0 binding 0; and the per-draw push constants (scene.h object_push).
layout(std140, row_major, set = 0, binding = 0) uniform frame_data {
  vec4 eye_world;            //   0
  mat4 view_from_world;      //  16
  mat4 clip_from_view;       //  80
  mat4 clip_from_world;      // 144
  mat4 world_from_clip;      // 208
  vec4 sun_toward;           // 272
  vec4 sun_color;            // 288
  vec4 ambient;              // 304
  vec4 point_position[3];    // 320: xyz, w radius
  vec4 point_color[3];       // 368
  vec4 viewport;             // 416
  uvec4 frame_info;          // 432: k, id clear, mode, 0
} frame;
