#version 460
#extension GL_GOOGLE_include_directive : require
// Fairy lights: a camera-facing quad (6 vertices) at each light, in eye space.
#include "common.glsl"

layout(location = 0) out vec2 outLocal;
layout(location = 1) flat out vec3 outColor;

void main() {
  const vec2 corners[6] = vec2[](vec2(-1, -1), vec2(1, -1), vec2(1, 1), vec2(-1, -1), vec2(1, 1), vec2(-1, 1));
  PointLight l = lights[visibleLights[gl_InstanceIndex]];
  vec2 c = corners[gl_VertexIndex];
  float size = l.eyePositionRadius.w * frame.params.y;
  vec3 eye = l.eyePositionRadius.xyz + vec3(c * size, 0.0);
  gl_Position = frame.clipFromEye * vec4(eye, 1.0);
  outLocal = c;
  outColor = l.color.rgb;
}
