#version 450
#extension GL_GOOGLE_include_directive : require
// The G-buffer: view-space position with linear depth (eye depth / far) in w, view-space normal
// stored as n * 0.5 + 0.5, albedo.
#include "frame.glsl"

layout(push_constant) uniform draw_block {
  mat4 world_from_object;
  vec4 albedo;
} draw;

layout(location = 0) in vec3 in_position_view;
layout(location = 1) in vec3 in_normal_view;
layout(location = 0) out vec4 out_position;
layout(location = 1) out vec4 out_normal;
layout(location = 2) out vec4 out_albedo;

void main() {
  vec3 n = normalize(in_normal_view);
  out_position = vec4(in_position_view, -in_position_view.z * frame.depth_params.z);
  out_normal = vec4(n * 0.5 + 0.5, 1.0);
  out_albedo = vec4(draw.albedo.rgb, 1.0);
}
