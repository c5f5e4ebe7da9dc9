#version 460
#extension GL_GOOGLE_include_directive : require
// Forward shading (Metal by Tutorials ch. 14, the seed's "for each model, for each fragment,
// for each light"): the material as the G-buffer pass evaluates it, then the sun and every
// visible point light, summed in registers and written to hdr once. Same formulas (shading.h),
// but from unrounded surface values: deferred reads them back from 8-bit albedo and fp16 normals.
// With COVERAGE on, each invocation adds the number of lights it evaluated to coverage_masked.
#include "common.glsl"
#include "material.glsl"
#include "shading.h"

#ifdef GB_EARLY_TESTS
// Opaque materials: depth test before the shader, so hidden fragments are not shaded (and not
// counted). Alpha-tested ones cannot: discard decides the depth write.
layout(early_fragment_tests) in;
#endif
layout(set = 1, binding = kBindingShadowMap) uniform sampler2DShadow shadowMap;
layout(set = 1, binding = kBindingCoverage, r32ui) uniform uimage2D coverage;

layout(location = 0) in vec3 inEye;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in vec4 inUv;
layout(location = 3) in vec4 inTangent;
layout(location = 4) in vec4 inLightClip;
layout(location = 5) flat in uint inMaterial;

layout(location = 0) out vec4 outColor;

void main() {
  Material m = materials[inMaterial];
  vec4 base = baseColor(m, inUv);
  if (ALPHA_TEST != 0 && base.a < m.params.y) discard;
  vec3 N = surfaceNormal(m, inNormal, inTangent, inUv, gl_FrontFacing, inEye);
  vec3 albedo = clamp(base.rgb, 0.0, 1.0);  // what an 8-bit albedo target would hold (unrounded)
  float specular = clamp(m.params.x, 0.0, 1.0);
  float shadow = 1.0;
  if (frame.sunEyeDirection.w > 0.0) {
    vec3 lc = inLightClip.xyz / inLightClip.w;
    shadow = texture(shadowMap, vec3(lc.xy * 0.5 + 0.5, lc.z));
  }
  if (m.flags.z != 0u) {  // unlit: the base colour as is (no lights evaluated, none counted)
    outColor = vec4(shadeUnlit(albedo), 1.0);
    return;
  }
  vec3 V = normalize(-inEye);
  vec3 c = shadeDirectional(albedo, specular, N, V, frame.sunEyeDirection.xyz, frame.sunColor.rgb, frame.ambientColor.rgb,
                            frame.sunEyeDirection.w > 0.0 ? shadow : 0.0);
  uint n = frame.counts.x;
  for (uint i = 0u; i < n; ++i) {
    PointLight l = lights[visibleLights[i]];
    c += shadePoint(albedo, specular, N, inEye, l.eyePositionRadius.xyz, l.eyePositionRadius.w, l.color.rgb);
  }
  if (COVERAGE != 0) imageAtomicAdd(coverage, ivec2(gl_FragCoord.xy), n);
  outColor = vec4(c, 1.0);
}
