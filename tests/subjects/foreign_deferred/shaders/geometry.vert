#version 450
#extension GL_GOOGLE_include_directive : require
// The G-buffer pass: view-space position and normal per vertex.
#include "frame.glsl"

layout(push_constant) uniform draw_block {
  mat4 world_from_object;
  vec4 albedo;
} draw;

layout(location = 0) in vec3 in_position;
layout(location = 1) in vec3 in_normal;
layout(location = 0) out vec3 out_position_view;
layout(location = 1) out vec3 out_normal_view;

void main() {
  vec4 view = frame.view_from_world * (draw.world_from_object * vec4(in_position, 1.0));
  out_position_view = view.xyz;
  // Rigid transforms with per-axis scales: the inverse transpose keeps normals perpendicular.
  mat3 normal_matrix = transpose(inverse(mat3(frame.view_from_world) * mat3(draw.world_from_object)));
  out_normal_view = normal_matrix * in_normal;
  gl_Position = frame.clip_from_view * view;
}
