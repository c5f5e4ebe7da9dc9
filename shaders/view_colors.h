// The colour maps of views, written once in the subset of GLSL that GLM also compiles: the viewer's
// view shader (view_map.frag) and the CPU mapping (views/analysis/visualize.cpp) draw the same colours.
#ifndef GBLENS_VIEW_COLORS_H
#define GBLENS_VIEW_COLORS_H

#ifdef __cplusplus
#include <cstdint>
#include <glm/glm.hpp>
namespace gb::colors {
using uint = uint32_t;
using vec2 = glm::vec2;
using vec3 = glm::vec3;
using glm::abs;
using glm::atan;
using glm::clamp;
using glm::floor;
using glm::length;
using glm::mix;
#define GB_FN inline
#define GB_CONST_ARRAY(type, name, n) const type name[n] = {
#define GB_END_ARRAY }
#else
#define GB_FN
#define GB_CONST_ARRAY(type, name, n) const type name[n] = type[](
#define GB_END_ARRAY )
#endif

// Counts: 0 black, then blue -> cyan -> green -> yellow -> red at t = 1.
GB_FN vec3 heatColor(float t) {
  if (t <= 0.0) return vec3(0.0);
  float f = clamp(t, 0.0f, 1.0f) * 4.0f;
  int i = int(f) < 3 ? int(f) : 3;
  float a = f - float(i);
  vec3 lo = i == 0 ? vec3(0, 0, 1) : i == 1 ? vec3(0, 1, 1) : i == 2 ? vec3(0, 1, 0) : vec3(1, 1, 0);
  vec3 hi = i == 0 ? vec3(0, 1, 1) : i == 1 ? vec3(0, 1, 0) : i == 2 ? vec3(1, 1, 0) : vec3(1, 0, 0);
  return mix(lo, hi, a);
}

// False colour for depths and scalars: viridis (Smith & van der Walt, matplotlib, CC0), its table
// sampled at 33 evenly spaced points and interpolated linearly (within 2.7/255 of matplotlib's
// 256-entry table).
GB_CONST_ARRAY(vec3, kViridis, 33)
  vec3(0.267004, 0.004874, 0.329415), vec3(0.277018, 0.050344, 0.375715), vec3(0.282327, 0.094955, 0.417331),
  vec3(0.282884, 0.135920, 0.453427), vec3(0.278826, 0.175490, 0.483397), vec3(0.270595, 0.214069, 0.507052),
  vec3(0.258965, 0.251537, 0.524736), vec3(0.244972, 0.287675, 0.537260), vec3(0.229739, 0.322361, 0.545706),
  vec3(0.214298, 0.355619, 0.551184), vec3(0.199430, 0.387607, 0.554642), vec3(0.185556, 0.418570, 0.556753),
  vec3(0.172719, 0.448791, 0.557885), vec3(0.160665, 0.478540, 0.558115), vec3(0.149039, 0.508051, 0.557250),
  vec3(0.137770, 0.537492, 0.554906), vec3(0.127568, 0.566949, 0.550556), vec3(0.120565, 0.596422, 0.543611),
  vec3(0.120638, 0.625828, 0.533488), vec3(0.132268, 0.655014, 0.519661), vec3(0.157851, 0.683765, 0.501686),
  vec3(0.196571, 0.711827, 0.479221), vec3(0.246070, 0.738910, 0.452024), vec3(0.304148, 0.764704, 0.419943),
  vec3(0.369214, 0.788888, 0.382914), vec3(0.440137, 0.811138, 0.340967), vec3(0.515992, 0.831158, 0.294279),
  vec3(0.595839, 0.848717, 0.243329), vec3(0.678489, 0.863742, 0.189503), vec3(0.762373, 0.876424, 0.137064),
  vec3(0.845561, 0.887322, 0.099702), vec3(0.926106, 0.897330, 0.104071), vec3(0.993248, 0.906157, 0.143936)
GB_END_ARRAY;

GB_FN vec3 viridis(float t) {
  float f = clamp(t, 0.0f, 1.0f) * 32.0f;
  int i = int(f) < 31 ? int(f) : 31;
  return mix(kViridis[i], kViridis[i + 1], f - float(i));
}

// Ids: a colour per value from an integer hash (Wellons' "lowbias32", from his hash-prospector
// search), kept away from black; id 0 (commonly "nothing") is black.
GB_FN uint hashId(uint x) {
  x ^= x >> 16u;
  x *= 0x7feb352du;
  x ^= x >> 15u;
  x *= 0x846ca68bu;
  x ^= x >> 16u;
  return x;
}
GB_FN vec3 idColor(uint id) {
  if (id == 0u) return vec3(0.0);
  uint h = hashId(id);
  vec3 c = vec3(float(h & 255u), float((h >> 8u) & 255u), float((h >> 16u) & 255u)) / 255.0f;
  return vec3(0.2) + 0.8f * c;
}

// Stencil values: 0 black, every other value its own hue (golden-ratio steps around the hue circle,
// so neighbouring values differ most), full saturation and value.
GB_FN vec3 hueColor(float h) {
  h = (h - floor(h)) * 6.0f;
  return clamp(vec3(abs(h - 3.0f) - 1.0f, 2.0f - abs(h - 2.0f), 2.0f - abs(h - 4.0f)), 0.0f, 1.0f);
}
GB_FN vec3 stencilColor(uint v) {
  if (v == 0u) return vec3(0.0);
  return hueColor(float(v) * 0.618033988749895f);
}

// Motion: the colour wheel of Baker et al., "A Database and Evaluation Methodology for Optical
// Flow" (IJCV 2011): 55 hues in segments red-yellow 15, yellow-green 6, green-cyan 4, cyan-blue
// 11, blue-magenta 13, magenta-red 6; the direction picks the hue, the magnitude (1 at `maxLength`)
// the saturation; beyond it the colour darkens.
GB_FN vec3 wheelColor(int k) {
  if (k < 15) return vec3(1.0, float(k) / 15.0f, 0.0);
  k -= 15;
  if (k < 6) return vec3(1.0f - float(k) / 6.0f, 1.0, 0.0);
  k -= 6;
  if (k < 4) return vec3(0.0, 1.0, float(k) / 4.0f);
  k -= 4;
  if (k < 11) return vec3(0.0, 1.0f - float(k) / 11.0f, 1.0);
  k -= 11;
  if (k < 13) return vec3(float(k) / 13.0f, 0.0, 1.0);
  k -= 13;
  return vec3(1.0, 0.0, 1.0f - float(k) / 6.0f);
}
GB_FN vec3 motionColor(vec2 d, float maxLength) {
  float r = length(d) / (maxLength > 0.0f ? maxLength : 1.0f);
  float a = atan(-d.y, -d.x) / 3.14159265358979f;  // -1 .. 1
  float fk = (a + 1.0f) / 2.0f * 54.0f;
  int k0 = int(floor(fk));
  int k1 = k0 + 1 == 55 ? 0 : k0 + 1;
  vec3 c = mix(wheelColor(k0), wheelColor(k1), fk - float(k0));
  return r <= 1.0f ? vec3(1.0) - r * (vec3(1.0) - c) : c * 0.75f;
}

#ifdef __cplusplus
}  // namespace gb::colors
#endif
#undef GB_FN
#undef GB_CONST_ARRAY
#undef GB_END_ARRAY
#endif
