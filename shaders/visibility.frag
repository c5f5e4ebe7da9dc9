#version 460
#extension GL_GOOGLE_include_directive : require
// The visibility pass (--gbuffer visibility): depth, stencil and one id per pixel, packed as
// renderer/core/visibility.h says: ((draw + 1) << VISIBILITY_BITS) | gl_PrimitiveID. Alpha-tested
// materials cut out the same fragments as gbuffer.frag (the same baseColor at the same UVs).
#include "common.glsl"
#include "material.glsl"

layout(constant_id = kSpecVisibilityBits) const uint VISIBILITY_BITS = 1;

layout(location = 2) in vec4 inUv;
layout(location = 5) flat in uint inMaterial;
layout(location = 6) flat in uint inDraw;

layout(location = 0) out uint outVisibility;

void main() {
  if (ALPHA_TEST != 0) {
    Material m = materials[inMaterial];
    if (baseColor(m, inUv).a < m.params.y) discard;
  }
  outVisibility = ((inDraw + 1u) << VISIBILITY_BITS) | uint(gl_PrimitiveID);
}
