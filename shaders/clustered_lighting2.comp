#version 460
#extension GL_GOOGLE_include_directive : require
// clustered_lighting.comp with two pixels an invocation (GBLENS_LIGHTING_PIXELS=2, issue 39): the
// workgroup still covers one cluster tile and stages each of its clusters' lists once, but has
// half as many invocations, and invocation (x, y) shades pixels (x, 2y) and (x, 2y + 1). Where
// both are in the cluster being shaded, each staged light is read from shared memory once for two
// evaluations, and the loop and its branch are paid once for two: at 4K and 65536 lights on an
// H200 that overhead is a large part of the pass's issue slots (shadePointPrepared is ~56 FLOP).
// The pair is vertically adjacent, not kTileSize / 2 apart: neighbours are in the same cluster
// (the same depth slice) far more often, and only then is a load shared. A subgroup's loads still
// read runs of kTileSize consecutive pixels of a row, as in the one-pixel variant. Each pixel sums
// its lights in list order through the same functions, so the image is the one-pixel variant's
// bit for bit.
#include "clustered_pixel.glsl"

layout(local_size_x = kTileSize, local_size_y = kTileSize / 2u) in;

const uint kGroup = kTileSize * kTileSize;  // lights staged a round: two per invocation
const uint kInvocations = kGroup / 2u;
shared vec4 sLight[kGroup];  // xyz eye position, w 1 / radius^2
shared vec4 sColor[kGroup];
shared uint sNext;           // the smallest cluster index still to shade in the workgroup

// One pixel's share of a round: the n staged lights in order, added to c.
vec3 shadeStaged(const Surface s, const vec3 V, vec3 c, const uint n) {
  for (uint i = 0u; i < n; ++i)
    c += shadePointPrepared(s.albedo, s.specular, s.N, s.P, V, sLight[i].xyz, sLight[i].w, sColor[i].rgb);
  return c;
}

void main() {
  const ivec2 q = ivec2(gl_WorkGroupID.xy * kTileSize + uvec2(gl_LocalInvocationID.x, 2u * gl_LocalInvocationID.y));
  Pixel a = startPixel(q);
  Pixel b = startPixel(q + ivec2(0, 1));
  const uint local = gl_LocalInvocationIndex;

  // As in clustered_lighting.comp: the workgroup's clusters in increasing index, each staged once,
  // every branch around the barriers uniform over the workgroup.
  for (;;) {
    if (local == 0u) sNext = kNoCluster;
    barrier();
    const uint want = min(a.pending ? a.ci : kNoCluster, b.pending ? b.ci : kNoCluster);
    if (want != kNoCluster) atomicMin(sNext, want);
    barrier();
    const uint cur = sNext;
    if (cur == kNoCluster) break;
    const uvec4 ref = clusters[cur].info;  // the same load in every invocation
    const bool mineA = a.pending && a.ci == cur;
    const bool mineB = b.pending && b.ci == cur;
    for (uint base = 0u; base < ref.w; base += kGroup) {
      const uint n = min(kGroup, ref.w - base);
      if (local < n) stageLight(ref.z + base, local, sLight[local], sColor[local]);
      if (local + kInvocations < n)
        stageLight(ref.z + base, local + kInvocations, sLight[local + kInvocations], sColor[local + kInvocations]);
      barrier();
      if (mineA && mineB) {  // each light read once for both pixels
        for (uint i = 0u; i < n; ++i) {
          const vec4 light = sLight[i];
          const vec3 color = sColor[i].rgb;
          a.c += shadePointPrepared(a.s.albedo, a.s.specular, a.s.N, a.s.P, a.V, light.xyz, light.w, color);
          b.c += shadePointPrepared(b.s.albedo, b.s.specular, b.s.N, b.s.P, b.V, light.xyz, light.w, color);
        }
      } else if (mineA || mineB) {  // one of them (an edge between clusters): one loop for either
        const Surface s = mineA ? a.s : b.s;
        const vec3 c = shadeStaged(s, mineA ? a.V : b.V, mineA ? a.c : b.c, n);
        if (mineA) a.c = c;
        else b.c = c;
      }
      barrier();
    }
    if (mineA) {
      a.evaluated = ref.w;
      a.pending = false;
    }
    if (mineB) {
      b.evaluated = ref.w;
      b.pending = false;
    }
    barrier();  // sNext is reset by the next round
  }
  finishPixel(a);
  finishPixel(b);
}
