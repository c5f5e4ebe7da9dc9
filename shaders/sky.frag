#version 460
#extension GL_GOOGLE_include_directive : require
// Sky: a procedural gradient by world-space view direction, only where no geometry was drawn.
#include "common.glsl"

layout(location = 0) in vec2 inNdc;
layout(location = 0) out vec4 outColor;

void main() {
  vec4 e = frame.eyeFromClip * vec4(inNdc, 0.5, 1.0);
  vec3 dir = normalize(mat3(frame.worldFromEye) * (e.xyz / e.w));
  float h = dir.y;
  vec3 c = h >= 0.0 ? mix(frame.skyHorizon.rgb, frame.skyZenith.rgb, pow(h, 0.6))
                    : mix(frame.skyHorizon.rgb, frame.skyGround.rgb, pow(-h, 0.4));
  // The sun's disc, so shadows have a visible cause.
  if (frame.sunEyeDirection.w > 0.0) {
    vec3 toSun = normalize(mat3(frame.worldFromEye) * frame.sunEyeDirection.xyz);
    float d = dot(dir, toSun);
    c += frame.sunColor.rgb * (smoothstep(0.9995, 0.9998, d) * 4.0 + pow(max(d, 0.0), 256.0) * 0.3);
  }
  outColor = vec4(c, 1.0);
}
