#version 460
#extension GL_GOOGLE_include_directive : require
// One icosahedron per light (instanced): the light's sphere of influence is inscribed in it.
#include "common.glsl"

layout(location = 0) in vec3 inPosition;  // unit icosahedron (circumradius 1)
layout(location = 0) flat out uint outLight;

layout(constant_id = 10) const float ICOSAHEDRON_INRADIUS = 0.7946544722917661;

void main() {
  uint light = visibleLights[gl_InstanceIndex];
  PointLight l = lights[light];
  vec3 eye = l.eyePositionRadius.xyz + inPosition * (l.eyePositionRadius.w / ICOSAHEDRON_INRADIUS);
  gl_Position = frame.clipFromEye * vec4(eye, 1.0);
  outLight = light;
}
