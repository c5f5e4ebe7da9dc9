#version 460
#extension GL_GOOGLE_include_directive : require
// Clustered shading, step 4 (Olsson et al. 2012, shading): one invocation per pixel reads the
// G-buffer once, shades the sun and ambient term and every light of its cluster's list in
// visible-list order (deterministic), summed in registers, and writes hdr once. A workgroup is one
// cluster tile, so its pixels' clusters differ only by depth slice: it takes them one at a time
// and stages each list through shared memory, kGroup lights a round, every invocation loading one
// (the list -> light pair of loads runs once per light and workgroup, all in parallel, not once
// per light and pixel, one after another). Pixels whose cluster had no room or
// whose list overflowed test their bin's lights themselves (exact, slower).
// With COVERAGE on, coverage_masked gets the number of lights each geometry pixel evaluated.
#include "common.glsl"
#include "gbuffer_read.glsl"
#include "shading.h"
#include "cluster_common.glsl"
#include "sky.glsl"

layout(local_size_x = kTileSize, local_size_y = kTileSize) in;
layout(set = 1, binding = kBindingHdrStorage, GB_HDR_FORMAT) uniform writeonly image2D hdrOut;
layout(set = 1, binding = kBindingCoverage, r32ui) uniform writeonly uimage2D coverage;

const uint kGroup = kTileSize * kTileSize;
shared vec4 sLight[kGroup];  // xyz eye position, w 1 / radius^2
shared vec4 sColor[kGroup];
shared uint sNext;           // the smallest cluster index still to shade in the workgroup

vec3 shadeBin(const Surface s, const vec3 V, const ivec2 p, inout uint evaluated) {
  // No list: every light of the pixel's bin (its bits cover every surface point of the bin).
  vec3 c = vec3(0.0);
  const uint tile = (uint(p.y) / kClusterTile) * frame.clusterGrid.x + uint(p.x) / kClusterTile;
  const uint mask = binIndex(tile) * frame.clusterGrid.w;
  const uint words = (lightCounts.counts.x + 31u) / 32u;
  for (uint w = 0u; w < words; ++w)
    for (uint bits = binBits[mask + w]; bits != 0u; bits &= bits - 1u) {
      const PointLight l = lights[visibleLights[w * 32u + uint(findLSB(bits))]];
      const float r = l.eyePositionRadius.w;
      c += shadePointPrepared(s.albedo, s.specular, s.N, s.P, V, l.eyePositionRadius.xyz, 1.0 / (r * r), l.color.rgb);
      ++evaluated;
    }
  return c;
}

void main() {
  const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  const uint local = gl_LocalInvocationIndex;
  const bool inside = p.x < int(frame.viewport.x) && p.y < int(frame.viewport.y);
  Surface s;
  s.geometry = false;
  s.unlit = false;
  if (inside) s = readSurface(vec2(p) + 0.5);
  const bool lit = s.geometry && !s.unlit;
  const vec3 V = normalize(-s.P);
  vec3 c = vec3(0.0);
  uint evaluated = 0u;
  if (s.geometry && s.unlit) c = shadeUnlit(s.albedo);  // KHR_materials_unlit: no light changes its colour
  if (lit)
    c = shadeDirectional(s.albedo, s.specular, s.N, V, frame.sunEyeDirection.xyz, frame.sunColor.rgb,
                         frame.ambientColor.rgb, frame.sunEyeDirection.w > 0.0 ? s.shadow : 0.0);
  const uint ci = lit ? pixelClusters[uint(p.y) * uint(frame.viewport.x) + uint(p.x)] : kNoCluster;
  const uvec4 info = ci != kNoCluster ? clusters[ci].info : uvec4(0u, 0u, kListOverflow, 0u);
  const bool fromBin = lit && info.z == kListOverflow;
  bool pending = lit && !fromBin;  // a listed cluster whose lights this pixel has not shaded yet

  // The workgroup's clusters in increasing index, each staged once; every branch around the
  // barriers depends only on shared values, so it is uniform over the workgroup.
  for (;;) {
    if (local == 0u) sNext = kNoCluster;
    barrier();
    if (pending) atomicMin(sNext, ci);
    barrier();
    const uint cur = sNext;
    if (cur == kNoCluster) break;
    const uvec4 ref = clusters[cur].info;  // the same load in every invocation
    const bool mine = pending && ci == cur;
    for (uint base = 0u; base < ref.w; base += kGroup) {
      const uint n = min(kGroup, ref.w - base);
      if (local < n) {
        const PointLight l = lights[lightLists[ref.z + base + local]];
        const float r = l.eyePositionRadius.w;
        sLight[local] = vec4(l.eyePositionRadius.xyz, 1.0 / (r * r));
        sColor[local] = l.color;
      }
      barrier();
      if (mine)  // a subgroup without this cluster's pixels skips the loop as a whole
        for (uint i = 0u; i < n; ++i)
          c += shadePointPrepared(s.albedo, s.specular, s.N, s.P, V, sLight[i].xyz, sLight[i].w, sColor[i].rgb);
      barrier();
    }
    if (mine) {
      evaluated = ref.w;
      pending = false;
    }
    barrier();  // sNext is reset by the next round
  }
  if (fromBin) c += shadeBin(s, V, p, evaluated);

  if (!inside) return;
  // No geometry: the sky (the skybox pass is skipped for this method), else nothing.
  const vec2 ndc = (vec2(p) + 0.5) * frame.viewport.zw * 2.0 - 1.0;
  imageStore(hdrOut, p, s.geometry ? vec4(c, 1.0) : skyEnabled() ? vec4(skyColor(ndc), 1.0) : vec4(0.0));
  if (COVERAGE != 0) imageStore(coverage, p, uvec4(evaluated));
}
