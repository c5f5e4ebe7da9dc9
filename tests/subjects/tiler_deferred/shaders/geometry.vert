#version 450
#extension GL_GOOGLE_include_directive : require
// tiler_deferred: the G-buffer pass's vertex shader (both modes): world-space normal and view depth out.
#include "frame.glsl"
#include "object.glsl"
layout(location = 0) in vec3 in_position;
layout(location = 1) in vec3 in_normal;
layout(location = 0) out vec3 out_normal_world;
layout(location = 1) out float out_view_depth;
void main() {
  const vec4 world = object.world_from_object * vec4(in_position, 1.0);
  const vec4 view = frame.view_from_world * world;
  out_normal_world = mat3(object.world_from_object) * in_normal;  // rotations about Z and axis scales only
  out_view_depth = view.z;                                         // left-handed view: +Z forward
  gl_Position = frame.clip_from_view * view;
}
