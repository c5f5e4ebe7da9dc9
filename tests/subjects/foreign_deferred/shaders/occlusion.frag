#version 450
#extension GL_GOOGLE_include_directive : require
// The second pass: screen-space ambient occlusion from the position and normal targets (a fixed
// spiral of 12 taps, no noise: the same texels every run). Background: 1 (unoccluded).
#include "frame.glsl"

layout(set = 0, binding = 1) uniform sampler2D position_target;
layout(set = 0, binding = 2) uniform sampler2D normal_target;
layout(location = 0) out float out_occlusion;

const int taps = 12;
const float radius_world = 1.0;

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  vec4 p = texelFetch(position_target, pixel, 0);
  if (p.w >= 1.0) {
    out_occlusion = 1.0;
    return;
  }
  vec3 n = normalize(texelFetch(normal_target, pixel, 0).xyz * 2.0 - 1.0);
  float eye_depth = -p.z;
  // Pixels per world unit at this depth: projection scale * half the height, over the depth unless orthographic.
  float pixels_per_unit = abs(frame.clip_from_view[1][1]) * 0.5 * frame.viewport.y;
  if (frame.depth_params.w < 0.5) pixels_per_unit /= eye_depth;
  float radius_px = clamp(radius_world * pixels_per_unit, 2.0, 32.0);
  ivec2 size = textureSize(position_target, 0);
  float sum = 0.0;
  for (int i = 0; i < taps; ++i) {
    float t = (float(i) + 0.5) / float(taps);
    float angle = 7.0 * 6.2831853 * t / float(taps) + 2.4 * float(i);
    ivec2 q = clamp(pixel + ivec2(round(vec2(cos(angle), sin(angle)) * t * radius_px)), ivec2(0), size - 1);
    vec4 s = texelFetch(position_target, q, 0);
    if (s.w >= 1.0) continue;
    vec3 v = s.xyz - p.xyz;
    float d2 = dot(v, v);
    float range = clamp(1.0 - d2 / (radius_world * radius_world * 4.0), 0.0, 1.0);
    sum += range * max(0.0, dot(v, n) - 0.01 * eye_depth) / (d2 + 0.01);
  }
  out_occlusion = clamp(1.0 - 4.0 * sum / float(taps), 0.0, 1.0);
}
