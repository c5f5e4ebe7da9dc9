#version 460
#extension GL_GOOGLE_include_directive : require
// Tiled deferred lighting (Lauritzen 2010, Olsson & Assarsson 2011): one workgroup per 16x16
// tile. The tile's surface points (read from the G-buffer once per pixel) bound an eye-space
// box, its depth bounds included; each round tests 256 visible lights against that box, one per
// invocation, into a shared bit list; then every pixel shades the listed lights in visible-list
// order (deterministic) and writes hdr once: sun + ambient + point lights, summed in registers.
// With COVERAGE on, coverage_masked gets the number of lights each geometry pixel evaluated.
#include "common.glsl"
#include "gbuffer_read.glsl"
#include "shading.h"
#include "sky.glsl"

layout(local_size_x = kTileSize, local_size_y = kTileSize) in;
layout(set = 1, binding = kBindingHdrStorage, GB_HDR_FORMAT) uniform writeonly image2D hdrOut;
layout(set = 1, binding = kBindingCoverage, r32ui) uniform writeonly uimage2D coverage;

const uint kGroup = kTileSize * kTileSize;
const uint kWords = kGroup / 32u;
shared uint sLo[3], sHi[3];  // box of the tile's surface points, as order-preserving uints
shared uint sList[kWords];   // bit k: light base + k reaches the box

// Float <-> uint with the same order (for atomicMin/Max on signed floats).
uint ordered(float f) {
  uint b = floatBitsToUint(f);
  return (b & 0x80000000u) != 0u ? ~b : b | 0x80000000u;
}
float unordered(uint u) { return uintBitsToFloat((u & 0x80000000u) != 0u ? u & 0x7FFFFFFFu : ~u); }

void main() {
  const uint local = gl_LocalInvocationIndex;
  if (local < 3u) {
    sLo[local] = 0xFFFFFFFFu;
    sHi[local] = 0u;
  }
  if (local < kWords) sList[local] = 0u;
  barrier();

  const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  const bool inside = p.x < int(frame.viewport.x) && p.y < int(frame.viewport.y);
  Surface s;
  s.geometry = false;
  s.unlit = false;
  if (inside) s = readSurface(vec2(p) + 0.5);
  if (s.geometry)
    for (int a = 0; a < 3; ++a) {
      atomicMin(sLo[a], ordered(s.P[a]));
      atomicMax(sHi[a], ordered(s.P[a]));
    }
  barrier();
  const bool anyGeometry = sHi[0] != 0u;  // ordered() of any float is non-zero
  const vec3 lo = vec3(unordered(sLo[0]), unordered(sLo[1]), unordered(sLo[2]));
  const vec3 hi = vec3(unordered(sHi[0]), unordered(sHi[1]), unordered(sHi[2]));

  vec3 c = vec3(0.0);
  if (s.geometry && s.unlit)
    c = shadeUnlit(s.albedo);
  else if (s.geometry)
    c = shadeDirectional(s.albedo, s.specular, s.N, normalize(-s.P), frame.sunEyeDirection.xyz, frame.sunColor.rgb,
                         frame.ambientColor.rgb, frame.sunEyeDirection.w > 0.0 ? s.shadow : 0.0);
  uint evaluated = 0u;
  const uint n = anyGeometry ? lightCounts.counts.x : 0u;  // uniform over the workgroup
  for (uint base = 0u; base < n; base += kGroup) {
    // Bin: the light reaches the box when the box's nearest point to its centre is inside its
    // radius. A surface point inside the sphere is inside the box, so nothing that lights a
    // pixel is dropped; the relative margin covers rounding of the box distance.
    const uint i = base + local;
    if (i < n) {
      const vec4 l = visiblePositions[i];
      vec3 d = max(max(lo - l.xyz, l.xyz - hi), 0.0);
      float r = l.w;
      if (dot(d, d) < r * r * 1.0001) atomicOr(sList[local >> 5], 1u << (local & 31u));
    }
    barrier();
    // Shade: every pixel walks the same list (uniform control flow, scalar light loads).
    for (uint w = 0u; w < kWords; ++w) {
      uint bits = sList[w];
      evaluated += bitCount(bits);
      while (bits != 0u) {
        uint k = uint(findLSB(bits));
        bits &= bits - 1u;
        PointLight l = lights[visibleLights[base + w * 32u + k]];
        if (s.geometry && !s.unlit)
          c += shadePoint(s.albedo, s.specular, s.N, s.P, l.eyePositionRadius.xyz, l.eyePositionRadius.w, l.color.rgb);
      }
    }
    barrier();
    if (local < kWords) sList[local] = 0u;
    barrier();
  }
  if (inside) {
    // No geometry: the sky (the skybox pass is skipped for this method), else nothing.
    const vec2 ndc = (vec2(p) + 0.5) * frame.viewport.zw * 2.0 - 1.0;
    imageStore(hdrOut, p, s.geometry ? vec4(c, 1.0) : skyEnabled() ? vec4(skyColor(ndc), 1.0) : vec4(0.0));
    if (COVERAGE != 0) imageStore(coverage, p, uvec4(s.geometry ? evaluated : 0u));
  }
}
