// How normal_shadow stores a unit normal and the shadow term, per NORMAL_ENCODING.

#include "octahedral.glsl"

// Precise octahedral encoding (Cigolle et al., JCGT 2014): of the four codes around the projection
// (floor/ceil of each coordinate, `scale` = the largest snorm code), the one whose decoded direction
// is closest to n; returned as code / scale, which the snorm attachment stores as that code.
// Closest by the squared chord |d - n|^2 (monotonic in the angle), not by dot(d, n): at 16 bits
// the candidates' cosines differ by ~1e-9, below float's resolution near 1, while the chord's
// components (~1e-4) keep float's relative precision. The first of equal candidates wins, in the
// order (0,0), (1,0), (0,1), (1,1). CPU mirror:
// octQuantize (renderer/core/codec.cpp), tested against this one on the device.
vec2 octEncodePrecise(vec3 n, float scale) {
  vec2 base = floor(octEncode(n) * scale), best = base;
  float bestDistance = 8.0;
  for (int i = 0; i < 4; ++i) {
    vec2 c = clamp(base + vec2(float(i & 1), float(i >> 1)), -scale, scale);
    vec3 e = octDecode(c / scale) - n;
    float distance = dot(e, e);
    if (distance < bestDistance) {
      bestDistance = distance;
      best = c;
    }
  }
  return best / scale;
}

vec4 encodeNormalShadow(vec3 n, float shadow) {
  if (NORMAL_ENCODING == kNormalOctRg16) return vec4(OCT_PRECISE != 0 ? octEncodePrecise(n, 32767.0) : octEncode(n), 0.0, shadow);
  if (NORMAL_ENCODING == kNormalRgb10a2) return vec4(n * 0.5 + 0.5, shadow);
  return vec4(n, shadow);
}

// An unlit surface (KHR_materials_unlit) has no normal: its texel holds the zero vector, which no
// unit normal stores (oct-rg16, whose x and y always decode to a unit vector, marks it in its
// unused z instead). The lighting passes show its albedo as is.
vec4 encodeUnlit() {
  if (NORMAL_ENCODING == kNormalOctRg16) return vec4(0.0, 0.0, 1.0, 1.0);
  if (NORMAL_ENCODING == kNormalRgb10a2) return vec4(0.5, 0.5, 0.5, 1.0);
  return vec4(0.0, 0.0, 0.0, 1.0);
}
bool unlitTexel(vec4 stored) {
  if (NORMAL_ENCODING == kNormalOctRg16) return stored.z > 0.5;
  vec3 n = NORMAL_ENCODING == kNormalRgb10a2 ? stored.xyz * 2.0 - 1.0 : stored.xyz;
  return dot(n, n) < 0.0625;  // stored unit normals are within a few percent of length 1
}

vec3 decodeNormal(vec4 stored) {
  if (NORMAL_ENCODING == kNormalOctRg16) return octDecode(stored.xy);
  if (NORMAL_ENCODING == kNormalRgb10a2) return normalize(stored.xyz * 2.0 - 1.0);
  return normalize(stored.xyz);
}
