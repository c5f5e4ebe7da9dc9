#version 460
#extension GL_GOOGLE_include_directive : require
// Clustered shading, step 3 (light assignment, fine): a workgroup per occupied cluster keeps the
// lights of its bin whose sphere reaches the cluster's box, in visible-list order, and lists their
// light indices (the shading pass loads lights[list[i]] with no visible-list step between): each
// invocation counts a contiguous run of the bin's mask words, an exclusive prefix over the
// invocations places each run, and the runs are written in order. (Keeping the passing bits in
// shared memory between the two walks, instead of testing again, was 3.5x slower on an H200: the
// 16 KiB a workgroup took cut the workgroups an SM runs at once, and the walks wait on loads.)
// A list that does not fit is marked kListOverflow (clustered_lighting then tests the bin's lights
// itself) and counted, and the CPU grows the list buffer for the next frame.
#include "common.glsl"
#include "cluster_common.glsl"

layout(local_size_x = kClusterListGroup) in;

shared uint sCount[kClusterListGroup];
shared uint sOffset;

void main() {
  const uint t = gl_LocalInvocationIndex;
  const uint total = min(header.counts.x, header.capacity.x);
  const uint words = (lightCounts.counts.x + 31u) / 32u;
  const uint per = (words + kClusterListGroup - 1u) / kClusterListGroup;
  const uint w0 = min(t * per, words), w1 = min(w0 + per, words);
  for (uint c = gl_WorkGroupID.x; c < total; c += gl_NumWorkGroups.x) {
    const Cluster cl = clusters[c];
    const uint mask = binIndex(cl.info.x) * frame.clusterGrid.w;
    uint n = 0u;
    for (uint w = w0; w < w1; ++w)
      for (uint bits = binBits[mask + w]; bits != 0u; bits &= bits - 1u) {
        const uint v = w * 32u + uint(findLSB(bits));
        n += sphereReachesBox(visiblePositions[v], cl.lo.xyz, cl.hi.xyz) ? 1u : 0u;
      }
    sCount[t] = n;
    barrier();
    if (t == 0u) {
      uint sum = 0u;
      for (uint i = 0u; i < kClusterListGroup; ++i) {
        const uint x = sCount[i];
        sCount[i] = sum;
        sum += x;
      }
      uint offset = atomicAdd(header.counts.y, sum);
      if (offset + sum > header.capacity.y) {
        offset = kListOverflow;
        atomicAdd(header.counts.z, 1u);
      }
      sOffset = offset;
      clusters[c].info.zw = uvec2(offset, sum);
    }
    barrier();
    if (sOffset != kListOverflow) {
      uint at = sOffset + sCount[t];
      for (uint w = w0; w < w1; ++w)
        for (uint bits = binBits[mask + w]; bits != 0u; bits &= bits - 1u) {
          const uint v = w * 32u + uint(findLSB(bits));
          if (sphereReachesBox(visiblePositions[v], cl.lo.xyz, cl.hi.xyz)) lightLists[at++] = visibleLights[v];
        }
    }
    barrier();  // sCount and sOffset are reused by the next cluster
  }
}
