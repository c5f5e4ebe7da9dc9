#version 450
// lighting_depth composite, second draw: a small sphere at each point light (instance i = light i).
#extension GL_GOOGLE_include_directive : require
#include "camera.glsl"

layout(location = 0) in vec3 in_pos;
layout(location = 0) flat out int v_light;

void main() {
  v_light = gl_InstanceIndex;
  gl_Position = cam.clip_from_world * vec4(lights.point_pos[gl_InstanceIndex].xyz + in_pos, 1.0);
}
