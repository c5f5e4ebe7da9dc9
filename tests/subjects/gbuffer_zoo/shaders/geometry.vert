#version 450
// Scene geometry of every mode: the object is objects[gl_InstanceIndex] (firstInstance = object
// index). The tangent frame goes to the fragment shader as it is (not normalised).
#extension GL_GOOGLE_include_directive : require
#include "camera.glsl"

layout(location = 0) in vec3 in_pos;
layout(location = 1) in vec3 in_normal;
layout(location = 2) in vec3 in_tangent;
layout(location = 3) in vec3 in_bitangent;
layout(location = 4) in vec2 in_uv;

layout(location = 0) out vec3 v_world;
layout(location = 1) out vec3 v_normal;
layout(location = 2) out vec3 v_tangent;
layout(location = 3) out vec3 v_bitangent;
layout(location = 4) out vec2 v_uv;
layout(location = 5) flat out uint v_object;

void main() {
  const mat4 model = objects[gl_InstanceIndex].world_from_object;
  const vec4 world = model * vec4(in_pos, 1);
  const mat3 turn = mat3(model);  // rigid: no inverse transpose needed
  v_world = world.xyz;
  v_normal = turn * in_normal;
  v_tangent = turn * in_tangent;
  v_bitangent = turn * in_bitangent;
  v_uv = in_uv;
  v_object = uint(gl_InstanceIndex);
  gl_Position = zoo_clip(world.xyz);
}
