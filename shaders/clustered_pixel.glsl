// clustered_lighting's per-pixel work around the cluster lists, shared by its variants of one and
// two pixels an invocation (clustered_lighting.comp, clustered_lighting2.comp): the G-buffer read
// and the sun before, the bin's lights (an overflowed list) and the stores after. Both variants sum
// a pixel's lights through these functions and shadePointPrepared in the same order, so they give
// the same image bit for bit; only how the staged lists reach the pixels differs.
#include "common.glsl"
#include "gbuffer_read.glsl"
#include "shading.h"
#include "cluster_common.glsl"
#include "sky.glsl"

layout(set = 1, binding = kBindingHdrStorage, GB_HDR_FORMAT) uniform writeonly image2D hdrOut;
layout(set = 1, binding = kBindingCoverage, r32ui) uniform writeonly uimage2D coverage;

// One pixel's state while its workgroup walks the clusters.
struct Pixel {
  ivec2 p;
  bool inside;     // in the viewport (a tile may reach past it)
  Surface s;
  vec3 V;          // unit, toward the eye
  vec3 c;          // what it has summed so far
  uint evaluated;  // lights evaluated (COVERAGE)
  uint ci;         // its cluster; kNoCluster where it is not lit or got none
  bool fromBin;    // its cluster's list overflowed: it tests its bin's lights itself
  bool pending;    // a listed cluster whose lights this pixel has not shaded yet
};

Pixel startPixel(const ivec2 p) {
  Pixel px;
  px.p = p;
  px.inside = p.x < int(frame.viewport.x) && p.y < int(frame.viewport.y);
  px.s.geometry = false;
  px.s.unlit = false;
  if (px.inside) px.s = readSurface(vec2(p) + 0.5);
  const bool lit = px.s.geometry && !px.s.unlit;
  px.V = normalize(-px.s.P);
  px.c = vec3(0.0);
  px.evaluated = 0u;
  if (px.s.geometry && px.s.unlit) px.c = shadeUnlit(px.s.albedo);  // KHR_materials_unlit: no light changes its colour
  if (lit)
    px.c = shadeDirectional(px.s.albedo, px.s.specular, px.s.N, px.V, frame.sunEyeDirection.xyz, frame.sunColor.rgb,
                            frame.ambientColor.rgb, frame.sunEyeDirection.w > 0.0 ? px.s.shadow : 0.0);
  px.ci = lit ? pixelClusters[uint(p.y) * uint(frame.viewport.x) + uint(p.x)] : kNoCluster;
  const uvec4 info = px.ci != kNoCluster ? clusters[px.ci].info : uvec4(0u, 0u, kListOverflow, 0u);
  px.fromBin = lit && info.z == kListOverflow;
  px.pending = lit && !px.fromBin;
  return px;
}

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

// After the lists: the bin's lights if the list overflowed, then hdr (the sky where no geometry
// is: the skybox pass is skipped for this method) and the count.
void finishPixel(Pixel px) {
  if (px.fromBin) px.c += shadeBin(px.s, px.V, px.p, px.evaluated);
  if (!px.inside) return;
  const vec2 ndc = (vec2(px.p) + 0.5) * frame.viewport.zw * 2.0 - 1.0;
  imageStore(hdrOut, px.p, px.s.geometry ? vec4(px.c, 1.0) : skyEnabled() ? vec4(skyColor(ndc), 1.0) : vec4(0.0));
  if (COVERAGE != 0) imageStore(coverage, px.p, uvec4(px.evaluated));
}

// Light i of the list staged in shared memory (xyz eye position, w 1 / radius^2; colour), read
// from the cluster's list at `list`.
void stageLight(const uint list, const uint i, out vec4 light, out vec4 color) {
  const PointLight l = lights[lightLists[list + i]];
  const float r = l.eyePositionRadius.w;
  light = vec4(l.eyePositionRadius.xyz, 1.0 / (r * r));
  color = l.color;
}
