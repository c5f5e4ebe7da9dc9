#version 450
#extension GL_GOOGLE_include_directive : require
// The lighting pass: a sun and four point lights (Lambert, smooth windowed falloff), ambient scaled
// by the occlusion target, into a half-float HDR target. Background: a constant sky.
#include "frame.glsl"

layout(set = 0, binding = 1) uniform sampler2D position_target;
layout(set = 0, binding = 2) uniform sampler2D normal_target;
layout(set = 0, binding = 3) uniform sampler2D albedo_target;
layout(set = 0, binding = 4) uniform sampler2D occlusion_target;
layout(location = 0) out vec4 out_hdr;

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  vec4 p = texelFetch(position_target, pixel, 0);
  if (p.w >= 1.0) {
    out_hdr = vec4(0.35, 0.45, 0.65, 1.0);
    return;
  }
  vec3 n = normalize(texelFetch(normal_target, pixel, 0).xyz * 2.0 - 1.0);
  vec3 albedo = texelFetch(albedo_target, pixel, 0).rgb;
  float occlusion = texelFetch(occlusion_target, pixel, 0).r;
  vec3 light = frame.ambient.rgb * occlusion + frame.sun_color.rgb * max(dot(n, frame.sun_direction_view.xyz), 0.0);
  for (int i = 0; i < 4; ++i) {
    vec3 to_light = frame.light_position_view[i].xyz - p.xyz;
    float d = length(to_light);
    float window = clamp(1.0 - pow(d / frame.light_position_view[i].w, 4.0), 0.0, 1.0);
    light += frame.light_color[i].rgb * max(dot(n, to_light / d), 0.0) * window * window / (d * d + 1.0);
  }
  out_hdr = vec4(albedo * light, 1.0);
}
