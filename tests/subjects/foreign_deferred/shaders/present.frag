#version 450
// The final image: Reinhard tone mapping and the sRGB curve, written by hand into a UNORM target
// (the stored bytes are sRGB-encoded; the format does not say so).
layout(set = 0, binding = 1) uniform sampler2D hdr_target;
layout(location = 0) out vec4 out_color;

vec3 srgb_encode(vec3 c) {
  return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, greaterThan(c, vec3(0.0031308)));
}

void main() {
  vec3 hdr = texelFetch(hdr_target, ivec2(gl_FragCoord.xy), 0).rgb;
  out_color = vec4(srgb_encode(hdr / (1.0 + hdr)), 1.0);
}
