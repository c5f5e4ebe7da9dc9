#version 450
// lighting_depth composite, full-screen part: world position from hardware depth through
// world_from_clip, world-space shading; depth 1 (the clear) is the sky.
#extension GL_GOOGLE_include_directive : require
#include "camera.glsl"
#include "shading.glsl"

layout(set = 0, binding = 3) uniform sampler2D g_albedo;
layout(set = 0, binding = 4) uniform sampler2D g_normal;
layout(set = 0, binding = 5) uniform sampler2D g_depth;
layout(location = 0) out vec4 o_radiance;

void main() {
  const ivec2 px = ivec2(gl_FragCoord.xy);
  const float d = texelFetch(g_depth, px, 0).r;
  if (d == 1.0) {
    o_radiance = vec4(zoo_sky(cam.viewport.y), 1.0);
    return;
  }
  const vec4 a = texelFetch(g_albedo, px, 0), n = texelFetch(g_normal, px, 0);
  const vec4 w = cam.world_from_clip * vec4(zoo_ndc(cam.viewport.xy), d, 1.0);
  const vec3 c = zoo_shade(w.xyz / w.w, normalize(n.xyz * 2.0 - 1.0), cam.eye_world.xyz, a.rgb, a.a, n.a, 1.0,
                           mat4(1.0));
  o_radiance = vec4(c, 1.0);
}
