#version 460
#extension GL_GOOGLE_include_directive : require
// tonemap_compute (--tonemap-pass): hdr -> final in compute, final written through its UNORM
// storage view, so the sRGB encoding the raster pass's attachment does is done here. The same
// toneMap (shading.h) and NaN -> 0 as tonemap.frag.
#include "common.glsl"
#include "shading.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 1, binding = kBindingHdr) uniform sampler2D hdr;
layout(set = 1, binding = kBindingClearTarget, rgba8) uniform writeonly image2D finalImage;

// The sRGB transfer function (IEC 61966-2-1), linear [0, 1] -> encoded [0, 1].
vec3 srgbEncode(vec3 c) {
  return mix(1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, 12.92 * c, lessThanEqual(c, vec3(0.0031308)));
}

void main() {
  const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, imageSize(finalImage)))) return;
  vec3 c = texelFetch(hdr, p, 0).rgb;
  c = mix(c, vec3(0.0), isnan(c));  // NaN never reaches the screen (the views flag it instead)
  imageStore(finalImage, p, vec4(srgbEncode(toneMap(c, frame.params.x)), 1.0));
}
