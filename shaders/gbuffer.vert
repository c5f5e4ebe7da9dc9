#version 460
#extension GL_GOOGLE_include_directive : require
// G-buffer (and forward) vertex stage: eye-space position via the camera-relative eyeFromObject.
// GB_VISIBILITY (the visibility pass, --gbuffer visibility): the same position, and only what the
// alpha test and the id need (the UVs, the material, the draw).
#include "common.glsl"

layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in vec2 inUv0;
layout(location = 3) in vec2 inUv1;
layout(location = 4) in vec4 inTangent;

#ifndef GB_VISIBILITY
layout(location = 0) out vec3 outEye;
layout(location = 1) out vec3 outNormal;
layout(location = 2) out vec4 outUv;
layout(location = 3) out vec4 outTangent;
layout(location = 4) out vec4 outLightClip;
layout(location = 5) flat out uint outMaterial;
layout(location = 6) flat out uint outFirstPrimitive;
#else
layout(location = 2) out vec4 outUv;
layout(location = 5) flat out uint outMaterial;
layout(location = 6) flat out uint outDraw;
#endif

void main() {
  DrawData d = draws[gl_InstanceIndex];
  vec4 eye = d.eyeFromObject * vec4(inPosition, 1.0);
  gl_Position = frame.clipFromEye * eye;
#ifdef GB_VISIBILITY
  outUv = materialUvs(materials[d.info.x], inUv0, inUv1);
  outMaterial = d.info.x;
  outDraw = uint(gl_InstanceIndex);
#else
  outEye = eye.xyz;
  outNormal = mat3(d.normalEyeFromObject) * inNormal;
  outTangent = vec4(mat3(d.eyeFromObject) * inTangent.xyz, inTangent.w);
  outUv = materialUvs(materials[d.info.x], inUv0, inUv1);
  outLightClip = d.lightClipFromObject * vec4(inPosition, 1.0);
  outMaterial = d.info.x;
  outFirstPrimitive = d.info.z;
#endif
}
