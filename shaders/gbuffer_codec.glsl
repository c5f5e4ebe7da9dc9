// How normal_shadow stores a unit normal and the shadow term, per NORMAL_ENCODING.

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

vec4 encodeNormalShadow(vec3 n, float shadow) {
  if (NORMAL_ENCODING == kNormalOctRg16) return vec4(octEncode(n), 0.0, shadow);
  if (NORMAL_ENCODING == kNormalRgb10a2) return vec4(n * 0.5 + 0.5, shadow);
  return vec4(n, shadow);
}

vec3 decodeNormal(vec4 stored) {
  if (NORMAL_ENCODING == kNormalOctRg16) return octDecode(stored.xy);
  if (NORMAL_ENCODING == kNormalRgb10a2) return normalize(stored.xyz * 2.0 - 1.0);
  return normalize(stored.xyz);
}
