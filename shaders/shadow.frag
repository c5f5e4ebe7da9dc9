#version 460
#extension GL_GOOGLE_include_directive : require
// Shadow map, alpha-tested materials only: cut out the same texels as the G-buffer does.
#include "common.glsl"
#include "material.glsl"

layout(location = 0) in vec4 inUv;
layout(location = 1) flat in uint inMaterial;

void main() {
  Material m = materials[inMaterial];
  if (baseColor(m, inUv).a < m.params.y) discard;
}
