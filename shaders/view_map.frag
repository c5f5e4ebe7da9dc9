#version 460
#extension GL_GOOGLE_include_directive : require
// A view: one target mapped for people (ViewParams: mapping, channels, black/white point,
// NaN/Inf/negative highlights, texel grid, shadow-texel marks), nearest texel, at any zoom.
// GB_VIEW_UINT: the target holds integers (coverage counts).
#include "common.glsl"
#include "gbuffer_codec.glsl"
#include "view_colors.h"

layout(push_constant) uniform Push { ViewParams p; };
#ifdef GB_VIEW_UINT
layout(set = 1, binding = 0) uniform usampler2D source;
#else
layout(set = 1, binding = 0) uniform sampler2D source;
#endif
#ifdef GB_VIEW_MARK
layout(set = 1, binding = 1) uniform sampler2D eyeDepth;  // where each screen texel's surface is
#endif
#ifdef GB_VIEW_DIFF  // compare mode: the same target of capture B
#ifdef GB_VIEW_UINT
layout(set = 1, binding = 1) uniform usampler2D sourceB;
#else
layout(set = 1, binding = 1) uniform sampler2D sourceB;
#endif
#endif
layout(constant_id = kSpecOutputSrgb) const uint OUTPUT_SRGB = 0;
// The mapping (ViewParams mode.x) known when the pipeline is made: a CPU device (lavapipe) runs every
// branch a pixel block could take, so with the mapping chosen per pixel all nine colour maps ran for
// each pixel (160 ms of the viewer's 172 ms a frame at 1200x760); specialised, the others are gone.
layout(constant_id = kSpecViewMapping) const uint MAPPING = kViewMapColor;
layout(location = 0) out vec4 outColor;

float srgbEncode(float v) {
  v = clamp(v, 0.0, 1.0);
  return v <= 0.0031308 ? v * 12.92 : 1.055 * pow(v, 1.0 / 2.4) - 0.055;
}
float srgbDecode(float v) { return v <= 0.04045 ? v / 12.92 : pow((v + 0.055) / 1.055, 2.4); }

bool validTexel(float v) {
  uint predicate = p.mode.w;
  if (predicate == kRangePositive) return v > 0.0;
  if (predicate == kRangeBelowOne) return v < 1.0;
  if (predicate == kRangeNotFar) return v != farDepth();
  if (predicate == kRangeNotValue) return v != uintBitsToFloat(p.extra.y);
  return true;
}

// A value's place in [black, white]: linear, or (log) log(v / black) / log(white / black), where
// both ends must be positive (else the linear place).
float rangePlace(float x, float lo, float hi, uint flags) {
  if ((flags & kViewFlagLog) != 0 && lo > 0.0 && hi > lo && x > 0.0) return log(x / lo) / log(hi / lo);
  return (x - lo) / (hi != lo ? hi - lo : 1.0);
}

// Shadow-map texels the lookup of screen texel `t` reads (2x2 linear compare footprint).
bool samplesMarkedTexel(ivec2 t) {
#ifdef GB_VIEW_MARK
  float d = texelFetch(eyeDepth, t, 0).r;
  if (!(d > 0.0)) return false;
  vec2 ndc = (vec2(t) + 0.5) * frame.viewport.zw * 2.0 - 1.0;
  vec3 P = vec3(d * (ndc + frame.eyeRay.zw) * frame.eyeRay.xy, -d);
  vec4 lc = frame.lightClipFromEye * vec4(P, 1.0);
  vec2 st = (lc.xy / lc.w * 0.5 + 0.5) * vec2(p.mark.zw) - 0.5;
  ivec2 base = ivec2(floor(st));
  ivec2 k = p.mark.xy - base;
  return k.x >= 0 && k.x <= 1 && k.y >= 0 && k.y <= 1;
#else
  return false;
#endif
}

void main() {
  vec2 texelF = (gl_FragCoord.xy - p.transform.xy) / p.transform.z;
  ivec2 size = textureSize(source, 0);
  vec3 display;
  if (any(lessThan(texelF, vec2(0.0))) || any(greaterThanEqual(texelF, vec2(size)))) {
    // Outside the image: a dark checkerboard, so the image's edge is obvious.
    ivec2 c = ivec2(gl_FragCoord.xy) / 8;
    display = vec3(((c.x + c.y) & 1) == 0 ? 0.10 : 0.14);
  } else {
    ivec2 t = ivec2(texelF);
    vec4 v = vec4(texelFetch(source, t, 0));
    uint mask = p.mode.y, mapping = MAPPING, flags = p.mode.z;
    float lo = p.range.x, hi = p.range.y;
    float span = hi != lo ? hi - lo : 1.0;
    int first = findLSB(mask);
    bool nanFound = false, infFound = false, negFound = false;
    for (int c = 0; c < 4; ++c)
      if ((mask & (1u << c)) != 0) {
        nanFound = nanFound || isnan(v[c]);
        infFound = infFound || isinf(v[c]);
        negFound = negFound || v[c] < 0.0;
      }
#ifndef GB_VIEW_UINT
    bool empty = (flags & kViewFlagDecoded) != 0 && floatBitsToUint(v.x) == kEmptyTexel;
#else
    bool empty = false;
#endif
#ifdef GB_VIEW_DIFF
    if (mapping == kViewMapDiff) {
      // Largest |A - B| over the selected channels; a NaN on one side only counts as infinite.
      vec4 b = vec4(texelFetch(sourceB, t, 0));
      float d = 0.0;
      for (int c = 0; c < 4; ++c)
        if ((mask & (1u << c)) != 0) {
          bool na = isnan(v[c]), nb = isnan(b[c]);
          float e = na || nb ? (na == nb ? 0.0 : uintBitsToFloat(0x7F800000u)) : (v[c] == b[c] ? 0.0 : abs(v[c] - b[c]));
          d = max(d, e);
        }
      nanFound = infFound = negFound = false;
      display = d > 0.0 ? heatColor(max(d, hi * 1e-3) / max(hi, 1e-30)) : vec3(0.0);
    } else
#endif
    if (empty) {
      nanFound = infFound = negFound = false;
      display = vec3(0.0);
    } else if (mapping == kViewMapNormal) {
      vec3 n = v.xyz;
      bool blank = false;
      if ((flags & kViewFlagNativeNormal) != 0) {
        // Raw encodings may hold a zero normal; octahedral (0, 0) is +Z and rgb10a2 0 is (-1, -1, -1).
        bool raw = NORMAL_ENCODING != kNormalRgb10a2 && NORMAL_ENCODING != kNormalOctRg16;
        n = raw && v.xyz == vec3(0.0) ? vec3(0.0) : decodeNormal(v);
        blank = v == vec4(0.0);  // nothing drawn (the G-buffer clears to 0)
      }
      display = blank ? vec3(0.0) : (n - lo) / span;
      for (int c = 0; c < 3; ++c)
        if ((mask & (1u << c)) == 0) display[c] = 0.0;
    } else if (mapping == kViewMapColor) {
      display = (v.rgb * p.range.w - lo) / span;
      for (int c = 0; c < 3; ++c)
        if ((mask & (1u << c)) == 0) display[c] = 0.0;
    } else {
      float x = v[max(first, 0)];
      if (mapping == kViewMapGrey) {
        float place = rangePlace(x, lo, hi, flags);
        display = (flags & kViewFlagFalseColor) != 0 ? viridis(place) : vec3(place);
      } else if (mapping == kViewMapDepth) {
        float place = clamp(rangePlace(x, lo, hi, flags), 0.0, 1.0);
        display = !validTexel(x) ? vec3(0.0) : (flags & kViewFlagFalseColor) != 0 ? viridis(1.0 - place) : vec3(1.0 - 0.9 * place);
      } else if (mapping == kViewMapId) {
        display = idColor(uint(x));
      } else if (mapping == kViewMapStencil) {
        uint s = uint(x), bits = p.extra.x;
        display = stencilColor(bits != 0u ? s & bits : s);
      } else if (mapping == kViewMapMotion) {
        display = motionColor(vec2(v.x, v.y), hi);
      } else {
        display = heatColor(x / max(hi, 1.0));
      }
    }
    display = clamp(display, 0.0, 1.0);
    if ((flags & kViewFlagSrgb) != 0) display = vec3(srgbEncode(display.r), srgbEncode(display.g), srgbEncode(display.b));
    // Highlights after the mapping: the colours must not depend on the range.
    bool stripe = ((int(gl_FragCoord.x) + int(gl_FragCoord.y)) / 3 & 1) == 0;
    vec4 special = vec4(0.0);
    if ((flags & kViewFlagSpecials) != 0 && nanFound) special = GB_COLOR_NAN;
    else if ((flags & kViewFlagSpecials) != 0 && infFound) special = GB_COLOR_INF;
    else if ((flags & kViewFlagNegative) != 0 && negFound) special = GB_COLOR_NEGATIVE;
    if (special.a > 0.0) display = stripe ? special.rgb : special.rgb * 0.35;
    if ((flags & kViewFlagMark) != 0 && samplesMarkedTexel(t)) display = mix(display, GB_COLOR_MARK.rgb, stripe ? 0.85 : 0.5);
    // Texel grid at high zoom: a line along each texel's top and left edge.
    vec2 within = fract(texelF) * p.transform.z;
    if ((flags & kViewFlagGrid) != 0 && (within.x < 1.0 || within.y < 1.0)) display = mix(display, vec3(0.5), p.range.z);
  }
  if (OUTPUT_SRGB != 0) display = vec3(srgbDecode(display.r), srgbDecode(display.g), srgbDecode(display.b));
  outColor = vec4(display, 1.0);
}
