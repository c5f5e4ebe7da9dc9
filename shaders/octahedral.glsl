// The octahedral mapping of unit vectors, shared by the G-buffer codec (gbuffer_codec.glsl) and the
// viewer's decoding of stored frames (view_decode.comp); CPU mirror: renderer/core/codec.cpp.

// Octahedral mapping (Meyer et al. 2010) of a unit vector to [-1,1]^2 and back.
vec2 octEncode(vec3 n) {
  n /= abs(n.x) + abs(n.y) + abs(n.z);
  vec2 p = n.xy;
  if (n.z < 0.0) p = (1.0 - abs(n.yx)) * vec2(n.x >= 0.0 ? 1.0 : -1.0, n.y >= 0.0 ? 1.0 : -1.0);
  return p;
}
vec3 octDecode(vec2 p) {
  vec3 n = vec3(p, 1.0 - abs(p.x) - abs(p.y));
  if (n.z < 0.0) n.xy = (1.0 - abs(n.yx)) * vec2(n.x >= 0.0 ? 1.0 : -1.0, n.y >= 0.0 ? 1.0 : -1.0);
  return normalize(n);
}
