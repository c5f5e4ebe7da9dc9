#version 460
#extension GL_GOOGLE_include_directive : require
// hdr -> final (sRGB target encodes): exposure + exponential shoulder, never NaN or Inf.
#include "common.glsl"
#include "shading.h"

#ifdef GB_INPUT_ATTACHMENTS
layout(input_attachment_index = kInputHdr, set = 1, binding = kBindingHdr) uniform subpassInput hdr;
#else
layout(set = 1, binding = kBindingHdr) uniform sampler2D hdr;
#endif
layout(location = 0) out vec4 outColor;

void main() {
#ifdef GB_INPUT_ATTACHMENTS
  vec3 c = subpassLoad(hdr).rgb;
#else
  vec3 c = texelFetch(hdr, ivec2(gl_FragCoord.xy), 0).rgb;
#endif
  c = mix(c, vec3(0.0), isnan(c));  // NaN never reaches the screen (the views flag it instead)
  outColor = vec4(toneMap(c, frame.params.x), 1.0);
}
