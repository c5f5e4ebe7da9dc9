#version 460
#extension GL_GOOGLE_include_directive : require
// Directional light (the sun) + ambient, full screen, only where stencil marks geometry.
#include "common.glsl"
#include "gbuffer_read.glsl"
#include "shading.h"

layout(location = 0) out vec4 outColor;

void main() {
  Surface s = readSurface(gl_FragCoord.xy);
  if (s.unlit) {
    outColor = vec4(shadeUnlit(s.albedo), 1.0);
    return;
  }
  vec3 V = normalize(-s.P);
  vec3 c = shadeDirectional(s.albedo, s.specular, s.N, V, frame.sunEyeDirection.xyz, frame.sunColor.rgb,
                            frame.ambientColor.rgb, frame.sunEyeDirection.w > 0.0 ? s.shadow : 0.0);
  outColor = vec4(c, 1.0);
}
