#version 450
// world_tbn lighting: world-space shading from the stored positions; id 0 is the sky.
#extension GL_GOOGLE_include_directive : require
#include "camera.glsl"
#include "shading.glsl"

layout(set = 0, binding = 3) uniform sampler2D g_position;
layout(set = 0, binding = 4) uniform sampler2D g_normal;
layout(set = 0, binding = 5) uniform sampler2D g_albedo;
layout(location = 0) out vec4 o_radiance;

void main() {
  const ivec2 px = ivec2(gl_FragCoord.xy);
  const vec4 p = texelFetch(g_position, px, 0), n = texelFetch(g_normal, px, 0), a = texelFetch(g_albedo, px, 0);
  if (p.w == 0.0) {
    o_radiance = vec4(zoo_sky(cam.viewport.y), 1.0);
    return;
  }
  o_radiance = vec4(zoo_shade(p.xyz, normalize(n.xyz), cam.eye_world.xyz, a.rgb, n.w, a.a, 1.0, mat4(1.0)), 1.0);
}
