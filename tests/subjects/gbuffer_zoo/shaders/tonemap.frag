#version 450
// The post passes: radiance to display colour. world_tbn: ACES, sRGB encoded here (UNORM target);
// forward: Reinhard on luminance (the SRGB target encodes); lighting_depth: exponential, encoded
// here; linear_depth: ACES, encoded here (10-bit target); view_oct: exponential (SRGB target).
#extension GL_GOOGLE_include_directive : require
#include "camera.glsl"
#include "shading.glsl"
#include "codecs.glsl"

layout(set = 0, binding = 3) uniform sampler2D hdr;
layout(location = 0) out vec4 o_display;

void main() {
  const vec3 x = texelFetch(hdr, ivec2(gl_FragCoord.xy), 0).rgb;
#if ZOO_MODE == 1
  o_display = vec4(zoo_srgb_encode(zoo_aces(x)), 1.0);
#elif ZOO_MODE == 2
  o_display = vec4(zoo_reinhard(x), 1.0);
#elif ZOO_MODE == 3
  o_display = vec4(zoo_srgb_encode(zoo_expo(x)), 1.0);
#elif ZOO_MODE == 5
  o_display = vec4(zoo_srgb_encode(zoo_aces(x)), 1.0);
#else
  o_display = vec4(zoo_expo(x), 1.0);
#endif
}
