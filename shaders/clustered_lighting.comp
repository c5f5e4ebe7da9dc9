#version 460
#extension GL_GOOGLE_include_directive : require
// Clustered shading, step 4 (Olsson et al. 2012, shading): one invocation per pixel reads the
// G-buffer once, shades the sun and ambient term and every light of its cluster's list in
// visible-list order (deterministic), summed in registers, and writes hdr once. Pixels whose
// cluster had no room or whose list overflowed test their bin's lights themselves (exact, slower).
// With COVERAGE on, coverage_masked gets the number of lights each geometry pixel evaluated.
#include "common.glsl"
#include "gbuffer_read.glsl"
#include "shading.h"
#include "cluster_common.glsl"
#include "sky.glsl"

layout(local_size_x = kTileSize, local_size_y = kTileSize) in;
layout(set = 1, binding = kBindingHdrStorage, GB_HDR_FORMAT) uniform writeonly image2D hdrOut;
layout(set = 1, binding = kBindingCoverage, r32ui) uniform writeonly uimage2D coverage;

void main() {
  const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (p.x >= int(frame.viewport.x) || p.y >= int(frame.viewport.y)) return;
  const Surface s = readSurface(vec2(p) + 0.5);
  vec3 c = vec3(0.0);
  uint evaluated = 0u;
  if (s.geometry && s.unlit) {
    c = shadeUnlit(s.albedo);  // KHR_materials_unlit: no light changes its colour
  } else if (s.geometry) {
    c = shadeDirectional(s.albedo, s.specular, s.N, normalize(-s.P), frame.sunEyeDirection.xyz, frame.sunColor.rgb,
                         frame.ambientColor.rgb, frame.sunEyeDirection.w > 0.0 ? s.shadow : 0.0);
    const uint ci = pixelClusters[uint(p.y) * uint(frame.viewport.x) + uint(p.x)];
    const uvec4 info = ci != kNoCluster ? clusters[ci].info : uvec4(0u, 0u, kListOverflow, 0u);
    if (info.z != kListOverflow) {
      for (uint i = 0u; i < info.w; ++i) {
        const PointLight l = lights[visibleLights[lightLists[info.z + i]]];
        c += shadePoint(s.albedo, s.specular, s.N, s.P, l.eyePositionRadius.xyz, l.eyePositionRadius.w, l.color.rgb);
      }
      evaluated = info.w;
    } else {
      // No list: every light of the pixel's bin (its bits cover every surface point of the bin).
      const uint tile = (uint(p.y) / kClusterTile) * frame.clusterGrid.x + uint(p.x) / kClusterTile;
      const uint mask = binIndex(tile) * frame.clusterGrid.w;
      const uint words = (lightCounts.counts.x + 31u) / 32u;
      for (uint w = 0u; w < words; ++w)
        for (uint bits = binBits[mask + w]; bits != 0u; bits &= bits - 1u) {
          const PointLight l = lights[visibleLights[w * 32u + uint(findLSB(bits))]];
          c += shadePoint(s.albedo, s.specular, s.N, s.P, l.eyePositionRadius.xyz, l.eyePositionRadius.w, l.color.rgb);
          ++evaluated;
        }
    }
  }
  // No geometry: the sky (the skybox pass is skipped for this method), else nothing.
  const vec2 ndc = (vec2(p) + 0.5) * frame.viewport.zw * 2.0 - 1.0;
  imageStore(hdrOut, p, s.geometry ? vec4(c, 1.0) : skyEnabled() ? vec4(skyColor(ndc), 1.0) : vec4(0.0));
  if (COVERAGE != 0) imageStore(coverage, p, uvec4(evaluated));
}
