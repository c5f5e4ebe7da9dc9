#version 450
#extension GL_GOOGLE_include_directive : require
// tiler_deferred, mode msaa, render pass 1: fetches each of the 4 samples of the G-buffer, lights each and
// averages them into the single-sample lit target ("resolved in the shader"; no resolve attachment).
#include "frame.glsl"
#include "shade.glsl"
layout(set = 1, binding = 0) uniform sampler2DMS g_normal;
layout(set = 1, binding = 1) uniform sampler2DMS g_albedo;
layout(set = 1, binding = 2) uniform sampler2DMS g_depth;
layout(set = 1, binding = 3) uniform usampler2DMS g_id;
layout(location = 0) out vec4 out_lit;
void main() {
  const ivec2 texel = ivec2(gl_FragCoord.xy);
  vec4 sum = vec4(0.0);
  for (int s = 0; s < 4; ++s) {
    if ((texelFetch(g_id, texel, s).r & 0xF0000000u) == 0xF0000000u) {  // the clear value: nothing drawn
      sum += vec4(k_sky, 0.0);
      continue;
    }
    const vec4 a = texelFetch(g_albedo, texel, s);
    const vec3 n = normalize(texelFetch(g_normal, texel, s).xyz * 2.0 - 1.0);
    const vec3 p = world_position(gl_FragCoord.xy, texelFetch(g_depth, texel, s).r);
    sum += vec4(shade(a.rgb, a.a, 0.0, n, p), 1.0);
  }
  out_lit = sum * 0.25;
}
