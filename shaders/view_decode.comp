#version 460
#extension GL_GOOGLE_include_directive : require
// One view of a stored frame decoded on the GPU (the viewer's streamed frames): the texels as the CPU
// holds them (CpuImage, binding 0; the surface depth's, binding 1) into the decoded view image
// viewImage writes (views/analysis/visualize.cpp: the same values, empty texels kEmptyTexel, NaNs
// 0x7FC00000), and the view's automatic-range statistics per component (view_range.comp's slots;
// an integer view's minimum and maximum as the integers, not ordered floats).
// Operation for operation the CPU decoder's (renderer/core/decode.cpp), in float.
// GB_VIEW_UINT: an integer view (one R32_UINT component).
#include "shared.h"
#include "octahedral.glsl"
#include "range_order.glsl"

layout(local_size_x = 16, local_size_y = 16) in;
// What a view's parameters say about its texels and kind, as specialisation constants (the values of
// ViewDecodeParams, which views/ui/view_decode.cpp sets from them): lavapipe runs every branch a
// block of texels could take, so a shader for every kind would decode each texel every way.
layout(constant_id = 0) const uint KIND = kDecodeColor;          // mode.x
layout(constant_id = 1) const uint FLAGS = 0;                    // mode.z
layout(constant_id = 2) const uint COUNT = 1;                    // mode.y: the quantity's channels
layout(constant_id = 3) const uint TYPE = kPixelF32;             // texels.format.x
layout(constant_id = 4) const uint ENCODING = kEncodingFloat;    // texels.format.y
layout(constant_id = 5) const uint TEXEL_BYTES = 4;              // texels.format.w
layout(constant_id = 6) const uint CH0 = 0;                      // channels
layout(constant_id = 7) const uint CH1 = 1;
layout(constant_id = 8) const uint CH2 = 2;
layout(constant_id = 9) const uint CH3 = 3;
layout(constant_id = 10) const uint NORMAL = 0;                  // encoding.x
layout(constant_id = 11) const uint SURFACE = kDecodeSurfaceAll; // mode.w
layout(constant_id = 12) const uint SURFACE_TYPE = kPixelF32;    // surface.format.x
layout(constant_id = 13) const uint SURFACE_ENCODING = kEncodingFloat;
layout(constant_id = 14) const uint SURFACE_TEXEL_BYTES = 4;
layout(constant_id = 15) const uint SURFACE_CHANNEL = 0;         // encoding.y
layout(constant_id = 16) const uint RANGES = 4;                  // encoding.w: the components with range statistics (0: none)
const uint kRowsPerInvocation = 4u;
layout(push_constant) uniform Push { uvec4 select; };  // x the view's params
layout(set = 0, binding = 0, std430) readonly buffer Texels { uint texels[]; };
layout(set = 0, binding = 1, std430) readonly buffer SurfaceTexels { uint surfaceTexels[]; };
#ifdef GB_VIEW_UINT
const uint kComponents = 1u;
layout(set = 0, binding = 2, r32ui) uniform writeonly uimage2D decoded;
#else
layout(set = 0, binding = 2, rgba32ui) uniform writeonly uimage2D decoded;  // an RGBA32F image's bits
const uint kComponents = 4u;
#endif
layout(set = 0, binding = 3, std430) readonly buffer Params { ViewDecodeParams params[]; };
layout(set = 0, binding = 4, std430) buffer Results { RangeResult results[]; };

// layout.h NormalEncoding, in its order.
const uint kXyz = 0, kXyzUnorm = 1, kOct = 2, kOctUnorm = 3, kOct12 = 4, kSpheremap = 5, kLambert = 6;

uint typeBytes(uint type) {
  return type == kPixelU8 || type == kPixelI8 ? 1u : type == kPixelU32 || type == kPixelF32 ? 4u : 2u;
}

// CpuImage::raw: the stored bits of channel c of texel p (image coordinates).
#define GB_RAW_FETCH(NAME, BUFFER, TYPE_, TEXEL_BYTES_)                                        \
  uint NAME(uvec4 size, uvec2 p, uint c) {                                                     \
    uint bytes = typeBytes(TYPE_);                                                             \
    uint at = (p.y * size.x + p.x) * TEXEL_BYTES_ + c * bytes;                                 \
    uint word = BUFFER[at >> 2];                                                               \
    if (bytes == 4u) return word;                                                              \
    return bitfieldExtract(word, int((at & 3u) * 8u), int(bytes * 8u));                        \
  }
GB_RAW_FETCH(rawAt, texels, TYPE, TEXEL_BYTES)
GB_RAW_FETCH(surfaceRawAt, surfaceTexels, SURFACE_TYPE, SURFACE_TEXEL_BYTES)

float srgbToLinear(float v) { return v <= 0.04045 ? v / 12.92 : pow((v + 0.055) / 1.055, 2.4); }

// renderer/core/image.cpp decodeRaw.
float decodeRaw(uint type, uint encoding, uint c, uint r) {
  if (type == kPixelF32) return uintBitsToFloat(r);
  if (type == kPixelF16) return unpackHalf2x16(r).x;
  if (type == kPixelI8) return max(float(bitfieldExtract(int(r), 0, 8)) / 127.0, -1.0);
  if (type == kPixelI16) return max(float(bitfieldExtract(int(r), 0, 16)) / 32767.0, -1.0);
  float unormMax = type == kPixelU16 ? 65535.0 : 255.0;
  if (encoding == kEncodingUnorm) return float(r) / unormMax;
  if (encoding == kEncodingSrgb) return c == 3u ? float(r) / 255.0 : srgbToLinear(float(r) / 255.0);
  if (encoding == kEncodingUnorm10) return c == 3u ? float(r) / 3.0 : float(r) / 1023.0;
  if (encoding == kEncodingUnorm24) return float(r) / 16777215.0;
  return float(r);
}

bool inside(DecodeTexels t, uvec2 target) {
  return all(greaterThanEqual(target, t.size.zw)) && all(lessThan(target - t.size.zw, t.size.xy));
}

bool matches(DecodeMatch m, uint raw, float value) {
  if (m.codes.x == 1u) return value == m.value.x;
  if (m.codes.x == 2u) return raw == m.codes.y || raw == m.codes.z;
  return false;
}

// decode.cpp decodeEyeDepth's "nothing drawn": the background (a hardware depth without one: the far
// plane), or a camera distance not above 0 once scaled.
bool drawn(DecodeMatch background, bool hardware, vec2 scaleBias, uint raw, float v) {
  if (matches(background, raw, v)) return false;
  if (hardware) return true;
  float d = v * scaleBias.x + scaleBias.y;
  return d > 0.0 && !isinf(d);
}

bool hasSurface(ViewDecodeParams q, uvec2 target) {
  if (SURFACE == kDecodeSurfaceAll) return true;
  if (SURFACE == kDecodeSurfaceNone || !inside(q.surface, target)) return false;
  uint raw = surfaceRawAt(q.surface.size, target - q.surface.size.zw, SURFACE_CHANNEL);
  float v = decodeRaw(SURFACE_TYPE, SURFACE_ENCODING, SURFACE_CHANNEL, raw);
  return drawn(q.surfaceBackground, (FLAGS & kDecodeFlagSurfaceHardware) != 0u, q.values.zw, raw, v);
}

// decode.cpp decodeNormalValues.
vec3 normalValues(uint e, vec4 c, uvec4 raw) {
  if (e == kXyz) return c.xyz;
  if (e == kXyzUnorm) return c.xyz * 2.0 - 1.0;
  if (e == kOct) return octDecode(c.xy);
  if (e == kOctUnorm) return octDecode(c.xy * 2.0 - 1.0);
  if (e == kOct12) {  // 12 + 12 bits in three bytes
    uvec2 p = uvec2((raw.x << 4) | (raw.y >> 4), ((raw.y & 15u) << 8) | raw.z);
    return octDecode(vec2(p) / 4095.0 * 2.0 - 1.0);
  }
  if (e == kSpheremap) {
    vec2 fenc = c.xy * 4.0 - 2.0;
    float f = dot(fenc, fenc), g = sqrt(max(1.0 - f / 4.0, 0.0));
    return vec3(fenc * g, 1.0 - f / 2.0);
  }
  float r2 = dot(c.xy, c.xy), z = 1.0 - 2.0 * r2, s = sqrt(max(1.0 - z * z, 0.0));  // Lambert
  return vec3(r2 > 0.0 ? c.xy / sqrt(r2) * s : vec2(0.0), z);
}

shared uint sMin[4], sMax[4], sCount[4], sNan[4], sInf[4], sNeg[4];

// One invocation's statistics of a component over its texels (in registers: lavapipe runs shared
// atomics one lane at a time, so they are taken once an invocation, not once a texel).
struct Range {
  uint lo, hi, count, nan, inf, negative;
};
Range emptyRange() { return Range(0xFFFFFFFFu, 0u, 0u, 0u, 0u, 0u); }
void add(inout Range r, float v) {
  if (isnan(v)) ++r.nan;
  else if (isinf(v)) ++r.inf;
  else {
    uint o = orderedFromFloat(v);
    r.lo = min(r.lo, o);
    r.hi = max(r.hi, o);
    ++r.count;
    if (v < 0.0) ++r.negative;
  }
}
void share(uint k, Range r) {
  if (r.count > 0u) {
    atomicMin(sMin[k], r.lo);
    atomicMax(sMax[k], r.hi);
    atomicAdd(sCount[k], r.count);
  }
  if (r.nan > 0u) atomicAdd(sNan[k], r.nan);
  if (r.inf > 0u) atomicAdd(sInf[k], r.inf);
  if (r.negative > 0u) atomicAdd(sNeg[k], r.negative);
}

// The view's value at target texel `t` (visualize.cpp viewValue); false: no value there.
bool viewValue(ViewDecodeParams q, uvec2 t, out vec4 out_, out uint integer) {
  out_ = vec4(0.0);
  integer = 0u;
  uvec2 p = t - q.texels.size.zw;
  vec4 v = vec4(0.0);
  uvec4 raw = uvec4(0u);
  const uint channel[4] = uint[4](CH0, CH1, CH2, CH3);
  for (uint k = 0u; k < COUNT && k < 4u; ++k) {
    raw[k] = rawAt(q.texels.size, p, channel[k]);
    v[k] = decodeRaw(TYPE, ENCODING, channel[k], raw[k]);
  }
  const uint kind = KIND, flags = FLAGS;
  if (kind == kDecodeColor) {
    out_ = vec4(v.rgb, COUNT > 3u ? v.a : 1.0);
    if ((flags & kDecodeFlagSrgb) != 0u) out_.rgb = vec3(srgbToLinear(out_.r), srgbToLinear(out_.g), srgbToLinear(out_.b));
  } else if (kind == kDecodeScalar) {
    out_.x = v.x * q.values.x + q.values.y;
  } else if (kind == kDecodeVector) {
    for (uint k = 0u; k < COUNT && k < 4u; ++k) out_[k] = v[k] * q.values.x + q.values.y;
  } else if (kind == kDecodeNormal) {
    if (!hasSurface(q, t)) return false;
    vec3 n = normalValues(NORMAL, v, raw);
    float length_ = length(n);
    out_ = vec4(length_ > 0.0 && !isinf(length_) ? n / length_ : vec3(0.0), length_);
  } else if (kind == kDecodeDepth) {
    bool sun = (flags & kDecodeFlagSun) != 0u;
    if (sun ? matches(q.background, raw.x, v.x) : !drawn(q.background, (flags & kDecodeFlagHardware) != 0u, q.values.xy, raw.x, v.x))
      return false;
    out_.x = sun || (flags & kDecodeFlagHardware) != 0u ? v.x : v.x * q.values.x + q.values.y;
  } else if (kind == kDecodePosition) {
    if (!hasSurface(q, t)) return false;
    out_ = vec4(v.xyz, length((q.eyeFromStored * vec4(v.xyz, 1.0)).xyz));
  } else if (kind == kDecodeMotion) {
    vec2 m = v.xy * q.camera.xy;  // camera.xy: pixels per unit
    if ((flags & kDecodeFlagMotionYUp) != 0u) m.y = -m.y;
    out_.xy = (flags & kDecodeFlagToNext) != 0u ? -m : m;
  } else {  // kDecodeInteger: plain integers exactly, float channels rounded
    const bool exact = ENCODING == kEncodingUint && TYPE != kPixelF32 && TYPE != kPixelF16;
    uint whole = 0u;
    if (v.x > 0.0 && !isinf(v.x)) {
      whole = uint(v.x);
      if (v.x - float(whole) >= 0.5) whole += 1u;  // llround: halves away from 0
    }
    integer = exact ? raw.x : whole;
  }
  return true;
}

void main() {
  ViewDecodeParams q = params[select.x];
  if (RANGES != 0u && gl_LocalInvocationIndex < 4u) {
    uint k = gl_LocalInvocationIndex;
    sMin[k] = 0xFFFFFFFFu;
    sMax[k] = 0u;
    sCount[k] = sNan[k] = sInf[k] = sNeg[k] = 0u;
  }
  if (RANGES != 0u) barrier();  // no barrier without statistics: lavapipe runs a barrier's workgroup as coroutines
  Range range[4] = Range[4](emptyRange(), emptyRange(), emptyRange(), emptyRange());
  for (uint row = 0u; row < kRowsPerInvocation; ++row) {  // a workgroup: 16 x (16 * kRowsPerInvocation) texels
    uvec2 p = uvec2(gl_GlobalInvocationID.x, gl_WorkGroupID.y * 16u * kRowsPerInvocation + row * 16u + gl_LocalInvocationID.y);
    if (any(greaterThanEqual(p, q.texels.size.xy))) continue;
    vec4 value;
    uint integer;
    bool has = viewValue(q, p + q.texels.size.zw, value, integer);
#ifdef GB_VIEW_UINT
    imageStore(decoded, ivec2(p), uvec4(has ? integer : kEmptyTexel));
    if (RANGES != 0u && has) {  // the integers themselves (ids above 2^24 are no floats)
      range[0].lo = min(range[0].lo, integer);
      range[0].hi = max(range[0].hi, integer);
      ++range[0].count;
    }
#else
    uvec4 bits = uvec4(kEmptyTexel);
    if (has)
      for (uint c = 0u; c < 4u; ++c) bits[c] = isnan(value[c]) ? 0x7FC00000u : floatBitsToUint(value[c]);
    imageStore(decoded, ivec2(p), bits);
    if (RANGES != 0u && has && KIND == kDecodeMotion) add(range[0], length(value.xy));
    else if (RANGES != 0u && has)
      for (uint c = 0u; c < RANGES; ++c) add(range[c], value[c]);
#endif
  }
  if (RANGES == 0u) return;
  for (uint c = 0u; c < min(kComponents, RANGES); ++c) share(c, range[c]);
  barrier();
  if (gl_LocalInvocationIndex < min(kComponents, RANGES)) {
    uint k = gl_LocalInvocationIndex, slot = q.encoding.z + k;
    if (sCount[k] > 0u) {
      atomicMin(results[slot].minMax.x, sMin[k]);
      atomicMax(results[slot].minMax.y, sMax[k]);
      atomicAdd(results[slot].minMax.z, sCount[k]);
    }
    if (sNan[k] > 0u) atomicAdd(results[slot].minMax.w, sNan[k]);
    if (sInf[k] > 0u) atomicAdd(results[slot].counts.x, sInf[k]);
    if (sNeg[k] > 0u) atomicAdd(results[slot].counts.y, sNeg[k]);
  }
}
