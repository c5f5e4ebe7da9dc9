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
// clustered_lighting2.comp is the same with two pixels an invocation (GBLENS_LIGHTING_PIXELS=2).
#include "clustered_pixel.glsl"

layout(local_size_x = kTileSize, local_size_y = kTileSize) in;

const uint kGroup = kTileSize * kTileSize;
shared vec4 sLight[kGroup];  // xyz eye position, w 1 / radius^2
shared vec4 sColor[kGroup];
shared uint sNext;           // the smallest cluster index still to shade in the workgroup

void main() {
  Pixel px = startPixel(ivec2(gl_GlobalInvocationID.xy));
  const uint local = gl_LocalInvocationIndex;

  // The workgroup's clusters in increasing index, each staged once; every branch around the
  // barriers depends only on shared values, so it is uniform over the workgroup.
  for (;;) {
    if (local == 0u) sNext = kNoCluster;
    barrier();
    if (px.pending) atomicMin(sNext, px.ci);
    barrier();
    const uint cur = sNext;
    if (cur == kNoCluster) break;
    const uvec4 ref = clusters[cur].info;  // the same load in every invocation
    const bool mine = px.pending && px.ci == cur;
    for (uint base = 0u; base < ref.w; base += kGroup) {
      const uint n = min(kGroup, ref.w - base);
      if (local < n) stageLight(ref.z + base, local, sLight[local], sColor[local]);
      barrier();
      if (mine)  // a subgroup without this cluster's pixels skips the loop as a whole
        for (uint i = 0u; i < n; ++i)
          px.c += shadePointPrepared(px.s.albedo, px.s.specular, px.s.N, px.s.P, px.V, sLight[i].xyz, sLight[i].w,
                                     sColor[i].rgb);
      barrier();
    }
    if (mine) {
      px.evaluated = ref.w;
      px.pending = false;
    }
    barrier();  // sNext is reset by the next round
  }
  finishPixel(px);
}
