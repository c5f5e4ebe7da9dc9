#version 450
// y_down lighting: world-space shading from the stored positions (w 0 is the sky), ACES, written as
// linear (not sRGB-encoded) 8-bit display colour.
#extension GL_GOOGLE_include_directive : require
#include "camera.glsl"
#include "shading.glsl"
#include "codecs.glsl"

layout(set = 0, binding = 3) uniform sampler2D g_position;
layout(set = 0, binding = 4) uniform sampler2D g_normal;
layout(set = 0, binding = 5) uniform sampler2D g_albedo;
layout(location = 0) out vec4 o_display;

void main() {
  const ivec2 px = ivec2(gl_FragCoord.xy);
  const vec4 p = texelFetch(g_position, px, 0);
  vec3 c;
  if (p.w == 0.0) {
    c = zoo_sky(cam.frame_params.y);
  } else {
    const vec4 a = texelFetch(g_albedo, px, 0);
    const vec3 n = zoo_oct_decode(texelFetch(g_normal, px, 0).xy * 2.0 - 1.0);
    c = zoo_shade(p.xyz, n, cam.eye_world.xyz, a.rgb, a.a, 0.0, 1.0, mat4(1.0));
  }
  o_display = vec4(zoo_aces(c), 1.0);
}
