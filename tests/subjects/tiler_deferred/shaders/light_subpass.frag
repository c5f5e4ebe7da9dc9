#version 450
#extension GL_GOOGLE_include_directive : require
// tiler_deferred, mode subpass, subpass 1: reads the G-buffer as input attachments, writes lit.
#include "frame.glsl"
#include "shade.glsl"
layout(input_attachment_index = 0, set = 1, binding = 0) uniform subpassInput g_normal;    // attachment 1
layout(input_attachment_index = 1, set = 1, binding = 1) uniform subpassInput g_albedo;    // attachment 0
layout(input_attachment_index = 2, set = 1, binding = 2) uniform subpassInput g_material;  // attachment 2
layout(input_attachment_index = 3, set = 1, binding = 3) uniform subpassInput g_depth;     // attachment 3
layout(location = 0) out vec4 out_lit;
void main() {
  const vec4 n = subpassLoad(g_normal);
  if (round(n.a * 3.0) == 0.0) {  // flag 0: nothing drawn
    out_lit = vec4(k_sky, 0.0);
    return;
  }
  const vec4 a = subpassLoad(g_albedo);
  const vec2 m = subpassLoad(g_material).rg;
  const vec3 p = world_position(gl_FragCoord.xy, subpassLoad(g_depth).r);
  out_lit = vec4(shade(a.rgb, a.a, m.r, normalize(n.xyz * 2.0 - 1.0), p), 1.0);
}
