#version 450
#extension GL_GOOGLE_include_directive : require
// tiler_deferred, mode compute, render pass 1: lights each pixel from the compute-written albedo and normal
// and the raster pass's depth and id.
#include "frame.glsl"
#include "shade.glsl"
layout(set = 1, binding = 0) uniform sampler2D g_normal;
layout(set = 1, binding = 1) uniform sampler2D g_albedo;
layout(set = 1, binding = 2) uniform sampler2D g_depth;
layout(set = 1, binding = 3) uniform usampler2D g_id;
layout(location = 0) out vec4 out_lit;
void main() {
  const ivec2 texel = ivec2(gl_FragCoord.xy);
  if ((texelFetch(g_id, texel, 0).r & 0xF0000000u) == 0xF0000000u) {  // the clear value: nothing drawn
    out_lit = vec4(k_sky, 0.0);
    return;
  }
  const vec4 a = texelFetch(g_albedo, texel, 0);
  const vec3 n = normalize(texelFetch(g_normal, texel, 0).xyz);
  const vec3 p = world_position(gl_FragCoord.xy, texelFetch(g_depth, texel, 0).r);
  out_lit = vec4(shade(a.rgb, a.a, 0.0, n, p), 1.0);
}
