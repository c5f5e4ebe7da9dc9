#version 450
// linear_depth lighting: view position from the linear depth and the pixel's ray (proj_params),
// view-space shading; depth 0 (the clear) is the sky.
#extension GL_GOOGLE_include_directive : require
#include "camera.glsl"
#include "shading.glsl"
#include "codecs.glsl"

layout(set = 0, binding = 3) uniform sampler2D g_depth;
layout(set = 0, binding = 4) uniform sampler2D g_normal;
layout(set = 0, binding = 5) uniform sampler2D g_albedo;
layout(location = 0) out vec4 o_radiance;

void main() {
  const ivec2 px = ivec2(gl_FragCoord.xy);
  const float z = texelFetch(g_depth, px, 0).r;
  if (z == 0.0) {
    o_radiance = vec4(zoo_sky(cam.viewport.y), 1.0);
    return;
  }
  const vec2 ndc = zoo_ndc(cam.viewport.xy);
  const vec3 p = vec3(ndc.x * cam.proj_params.x * z, -ndc.y * cam.proj_params.y * z, -z);
  const vec4 n = texelFetch(g_normal, px, 0), a = texelFetch(g_albedo, px, 0);
  const vec3 c = zoo_shade(p, normalize(n.xyz), vec3(0.0), zoo_srgb_decode(a.rgb), n.w, a.a, 1.0, cam.view_from_world);
  o_radiance = vec4(c, 1.0);
}
