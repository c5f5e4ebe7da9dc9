#version 460
#extension GL_GOOGLE_include_directive : require
// Fairy light sprite: a procedural radial falloff, premultiplied alpha.
#include "common.glsl"

layout(location = 0) in vec2 inLocal;
layout(location = 1) flat in vec3 inColor;
layout(location = 0) out vec4 outColor;

void main() {
  float r2 = dot(inLocal, inLocal);
  if (r2 >= 1.0) discard;
  float a = (1.0 - r2) * (1.0 - r2);
  outColor = vec4(inColor * (0.6 + 2.4 * a * a) * a, a);
}
