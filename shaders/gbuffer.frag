#version 460
#extension GL_GOOGLE_include_directive : require
// G-buffer: albedo_specular, normal_shadow (normal + shadow-map compare), depth (eye depth);
// variants add primitive_id (GB_PRIMITIVE_ID), the stored position (GB_POSITION) and the motion
// target (GB_MOTION: pixels toward the previous frame, +y down, jitter excluded), in that order.
#include "common.glsl"
#include "material.glsl"
#include "gbuffer_codec.glsl"

layout(set = 1, binding = kBindingShadowMap) uniform sampler2DShadow shadowMap;

layout(location = 0) in vec3 inEye;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in vec4 inUv;
layout(location = 3) in vec4 inTangent;
layout(location = 4) in vec4 inLightClip;
layout(location = 5) flat in uint inMaterial;
layout(location = 6) flat in uint inFirstPrimitive;

layout(location = 0) out vec4 outAlbedoSpecular;
layout(location = 1) out vec4 outNormalShadow;
layout(location = 2) out float outDepth;
#ifdef GB_PRIMITIVE_ID
layout(location = 3) out uint outPrimitiveId;
#endif
#ifdef GB_POSITION
#ifdef GB_PRIMITIVE_ID
layout(location = 4) out vec4 outPosition;
#else
layout(location = 3) out vec4 outPosition;
#endif
#endif
#ifdef GB_MOTION
#ifdef GB_PRIMITIVE_ID
#define GB_ID_OUTPUTS 1
#else
#define GB_ID_OUTPUTS 0
#endif
#ifdef GB_POSITION
#define GB_POSITION_OUTPUTS 1
#else
#define GB_POSITION_OUTPUTS 0
#endif
layout(location = 3 + GB_ID_OUTPUTS + GB_POSITION_OUTPUTS) out vec2 outMotion;
#endif

void main() {
  Material m = materials[inMaterial];
  vec4 base = baseColor(m, inUv);
  if (ALPHA_TEST != 0 && base.a < m.params.y) discard;
  vec3 N = surfaceNormal(m, inNormal, inTangent, inUv, gl_FrontFacing, inEye);
  float shadow = 1.0;
  if (frame.sunEyeDirection.w > 0.0) {
    vec3 lc = inLightClip.xyz / inLightClip.w;
    shadow = texture(shadowMap, vec3(lc.xy * 0.5 + 0.5, lc.z));
  }
  outAlbedoSpecular = vec4(base.rgb, m.params.x);
  outNormalShadow = m.flags.z != 0u ? encodeUnlit() : encodeNormalShadow(N, shadow);
  outDepth = -inEye.z;
#ifdef GB_PRIMITIVE_ID
  outPrimitiveId = inFirstPrimitive + uint(gl_PrimitiveID);
#endif
#ifdef GB_POSITION
  // World position as the tutorials store it, or camera-relative (world axes): formed from the
  // camera-relative eye position, so only the stored format rounds far from the origin.
  vec3 relative = mat3(frame.worldFromEye) * inEye;
  outPosition = vec4(POSITION == kPositionWorld ? relative + frame.worldFromEye[3].xyz : relative, 1.0);
#endif
#ifdef GB_MOTION
  // The surface point's unjittered pixel in the previous frame minus the one in this frame: the
  // difference of NDCs first (no cancellation of pixel coordinates), then pixels (NDC y is +y down).
  vec4 previous = frame.prevClipFromEye * vec4(inEye, 1.0);
  vec4 current = frame.unjitteredClipFromEye * vec4(inEye, 1.0);
  vec2 ndc = previous.xy / previous.w - current.xy / current.w;
  outMotion = previous.w > 0.0 ? ndc * 0.5 * frame.viewport.xy : vec2(0.0);  // 0: behind the previous camera
#endif
}
