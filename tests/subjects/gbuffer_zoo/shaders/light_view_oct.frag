#version 450
// view_oct lighting: view position from reversed-Z depth through view_from_clip (depth 0, the clear,
// is the sky), octahedral normals decoded, view-space shading.
#extension GL_GOOGLE_include_directive : require
#include "camera.glsl"
#include "shading.glsl"
#include "codecs.glsl"

layout(set = 0, binding = 3) uniform sampler2D g_albedo;
layout(set = 0, binding = 4) uniform sampler2D g_normal;
layout(set = 0, binding = 5) uniform sampler2D g_material;
layout(set = 0, binding = 6) uniform sampler2D g_depth;
layout(location = 0) out vec4 o_radiance;

void main() {
  const ivec2 px = ivec2(gl_FragCoord.xy);
  const float d = texelFetch(g_depth, px, 0).r;
  if (d == 0.0) {
    o_radiance = vec4(zoo_sky(cam.viewport.y), 1.0);
    return;
  }
  const vec4 a = texelFetch(g_albedo, px, 0), m = texelFetch(g_material, px, 0);
  const vec4 v = cam.view_from_clip * vec4(zoo_ndc(cam.viewport.xy), d, 1.0);
  const vec3 n = zoo_oct_decode(texelFetch(g_normal, px, 0).xy);
  o_radiance = vec4(zoo_shade(v.xyz / v.w, n, vec3(0.0), a.rgb, m.r, m.g, m.b, cam.view_from_world[0]), 1.0);
}
