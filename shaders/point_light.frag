#version 460
#extension GL_GOOGLE_include_directive : require
// Point light: reconstruct the surface, evaluate one light, add into hdr (additive blending).
// With COVERAGE on, each invocation is counted into coverage_masked.
#include "common.glsl"
#include "gbuffer_read.glsl"
#include "shading.h"

// Depth/stencil tests before the shader: culling must stop the shader, and with it the coverage
// counter (a shader with side effects would otherwise run ahead of late tests).
layout(early_fragment_tests) in;
layout(set = 1, binding = kBindingCoverage, r32ui) uniform uimage2D coverage;
layout(location = 0) flat in uint inLight;
layout(location = 0) out vec4 outColor;

void main() {
  if (COVERAGE != 0) imageAtomicAdd(coverage, ivec2(gl_FragCoord.xy), 1u);
  Surface s = readSurface(gl_FragCoord.xy);
  vec3 c = vec3(0.0);
  PointLight l = lights[inLight];
  if (s.geometry && !s.unlit) c = shadePoint(s.albedo, s.specular, s.N, s.P, l.eyePositionRadius.xyz, l.eyePositionRadius.w, l.color.rgb);
  outColor = vec4(c, 0.0);
}
