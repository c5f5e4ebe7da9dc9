#version 460
#extension GL_GOOGLE_include_directive : require
// Automatic range of a view: min/max of one channel over the valid texels (RangeParams), with
// NaN/Inf/negative counts, reduced per workgroup, then into one RangeResult slot.
// GB_VIEW_UINT: the target holds integers (coverage counts).
#include "common.glsl"

layout(local_size_x = 16, local_size_y = 16) in;
layout(push_constant) uniform Push { RangeParams p; };
#ifdef GB_VIEW_UINT
layout(set = 1, binding = 0) uniform usampler2D source;
#else
layout(set = 1, binding = 0) uniform sampler2D source;
#endif
layout(set = 1, binding = 2, std430) buffer Results { RangeResult results[]; };

shared uint sMin, sMax, sCount, sNan, sInf, sNeg;

#include "range_order.glsl"

void main() {
  if (gl_LocalInvocationIndex == 0) {
    sMin = 0xFFFFFFFFu;
    sMax = 0u;
    sCount = sNan = sInf = sNeg = 0u;
  }
  barrier();
  ivec2 t = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = textureSize(source, 0);
  if (all(lessThan(t, size))) {
    float v = float(texelFetch(source, t, 0)[p.select.x]);
    bool valid = true;
    if (p.select.y == kRangePositive) valid = v > 0.0;
    else if (p.select.y == kRangeBelowOne) valid = v < 1.0;
    else if (p.select.y == kRangeNotFar) valid = v != farDepth();
    else if (p.select.y == kRangeNotValue) valid = v != uintBitsToFloat(p.select.w);
    if (isnan(v)) atomicAdd(sNan, 1u);
    else if (isinf(v)) atomicAdd(sInf, 1u);
    else if (valid) {
      uint o = orderedFromFloat(v);
      atomicMin(sMin, o);
      atomicMax(sMax, o);
      atomicAdd(sCount, 1u);
      if (v < 0.0) atomicAdd(sNeg, 1u);
    }
  }
  barrier();
  if (gl_LocalInvocationIndex == 0) {
    uint slot = p.select.z;
    if (sCount > 0u) {
      atomicMin(results[slot].minMax.x, sMin);
      atomicMax(results[slot].minMax.y, sMax);
      atomicAdd(results[slot].minMax.z, sCount);
    }
    if (sNan > 0u) atomicAdd(results[slot].minMax.w, sNan);
    if (sInf > 0u) atomicAdd(results[slot].counts.x, sInf);
    if (sNeg > 0u) atomicAdd(results[slot].counts.y, sNeg);
  }
}
