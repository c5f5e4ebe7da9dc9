#version 450
// Light markers: emissive; hidden where the G-buffer depth is nearer (the composite pass's own depth
// attachment only orders the markers among themselves).
#extension GL_GOOGLE_include_directive : require
#include "camera.glsl"

layout(set = 0, binding = 5) uniform sampler2D g_depth;
layout(location = 0) flat in int v_light;
layout(location = 0) out vec4 o_radiance;

void main() {
  if (gl_FragCoord.z > texelFetch(g_depth, ivec2(gl_FragCoord.xy), 0).r) discard;
  o_radiance = vec4(lights.point_color[v_light].rgb * 2.0, 1.0);
}
