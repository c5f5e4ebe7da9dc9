#version 460
#extension GL_GOOGLE_include_directive : require
// Shadow map: geometry from the sun's view. UVs are passed on only for alpha-tested materials.
#include "common.glsl"

layout(location = 0) in vec3 inPosition;
layout(location = 2) in vec2 inUv0;
layout(location = 3) in vec2 inUv1;

layout(location = 0) out vec4 outUv;
layout(location = 1) flat out uint outMaterial;

void main() {
  DrawData d = draws[gl_InstanceIndex];
  gl_Position = d.lightClipFromObject * vec4(inPosition, 1.0);
  outUv = materialUvs(materials[d.info.x], inUv0, inUv1);
  outMaterial = d.info.x;
}
