// foreign_deferred: the camera uniform buffer (scene.h, frame_uniforms), std140, set 0 binding 0.
layout(std140, set = 0, binding = 0) uniform frame_block {
  mat4 clip_from_view;          // 0: projection first
  mat4 view_from_world;         // 64
  mat4 clip_from_world;         // 128
  mat4 view_from_clip;          // 192
  vec4 sun_direction_view;      // 256
  vec4 sun_color;               // 272
  vec4 ambient;                 // 288
  vec4 depth_params;            // 304: near, far, 1/far, orthographic
  vec4 light_position_view[4];  // 320
  vec4 light_color[4];          // 384
  vec4 viewport;                // 448
} frame;
