#version 450
// stencil_dontcare lighting: view position from the depth aspect through view_from_clip, view-space
// shading, Reinhard, written straight to the SRGB display target (no separate post pass).
#extension GL_GOOGLE_include_directive : require
#include "camera.glsl"
#include "shading.glsl"

layout(set = 0, binding = 3) uniform sampler2D g_albedo;
layout(set = 0, binding = 4) uniform sampler2D g_normal;
layout(set = 0, binding = 5) uniform sampler2D g_material;
layout(set = 0, binding = 6) uniform sampler2D g_depth;
layout(location = 0) out vec4 o_display;

void main() {
  const ivec2 px = ivec2(gl_FragCoord.xy);
  const float d = texelFetch(g_depth, px, 0).r;
  vec3 c;
  if (d == 1.0) {
    c = zoo_sky(cam.viewport.y);
  } else {
    const vec4 a = texelFetch(g_albedo, px, 0), m = texelFetch(g_material, px, 0);
    const vec4 v = cam.view_from_clip * vec4(zoo_ndc(cam.viewport.xy), d, 1.0);
    const vec3 n = normalize(texelFetch(g_normal, px, 0).xyz);
    c = zoo_shade(v.xyz / v.w, n, vec3(0.0), a.rgb, m.r, m.g, a.a, cam.view_from_world);
  }
  o_display = vec4(zoo_reinhard(c), 1.0);
}
