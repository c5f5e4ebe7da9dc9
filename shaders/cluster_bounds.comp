#version 460
#extension GL_GOOGLE_include_directive : require
// Clustered shading, step 1 (Olsson et al. 2012, "cluster assignment" and "finding unique
// clusters"): one workgroup per 16x16 screen tile. Each pixel's surface point falls in an
// exponential depth slice; the tile's occupied slices become clusters (a shared bit mask, ranked
// by popcount), each with the box of its own surface points (explicit bounds, tighter than the
// slice's frustum piece). Clusters get consecutive indices from a global counter; each pixel
// records its cluster; the light bin's box grows by the tile's points.
#include "common.glsl"
#include "gbuffer_read.glsl"
#include "cluster_common.glsl"

layout(local_size_x = kClusterTile, local_size_y = kClusterTile) in;

const uint kGroup = kClusterTile * kClusterTile;
const uint kSliceWords = kClusterMaxSlices / 32u;
shared uint sSlices[kSliceWords];     // bit k: slice k holds a surface point of the tile
shared uint sLo[kGroup * 3u], sHi[kGroup * 3u];  // per local cluster: ordered min, ~ordered max
shared uint sBase;                    // the tile's first cluster index (kNoCluster: no room)

void main() {
  const uint local = gl_LocalInvocationIndex;
  if (local < kSliceWords) sSlices[local] = 0u;
  for (uint i = local; i < kGroup * 3u; i += kGroup) {
    sLo[i] = 0xFFFFFFFFu;
    sHi[i] = 0xFFFFFFFFu;
  }
  barrier();

  const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  const bool inside = p.x < int(frame.viewport.x) && p.y < int(frame.viewport.y);
  vec3 P = vec3(0.0);
  const bool geometry = inside && readPosition(vec2(p) + 0.5, P);
  const uint slice = geometry ? depthSlice(P) : 0u;
  if (geometry) atomicOr(sSlices[slice >> 5], 1u << (slice & 31u));
  barrier();

  // Rank of the pixel's slice among the occupied ones = its cluster within the tile.
  uint rank = 0u, occupied = 0u;
  for (uint w = 0u; w < kSliceWords; ++w) {
    uint bits = sSlices[w];
    if (w < (slice >> 5)) rank += bitCount(bits);
    else if (w == (slice >> 5)) rank += bitCount(bits & ((1u << (slice & 31u)) - 1u));
    occupied += bitCount(bits);
  }
  if (geometry)
    for (int a = 0; a < 3; ++a) {
      atomicMin(sLo[rank * 3u + a], ordered(P[a]));
      atomicMin(sHi[rank * 3u + a], ~ordered(P[a]));
    }
  if (local == 0u) {
    sBase = kNoCluster;
    if (occupied > 0u) {
      uint base = atomicAdd(header.counts.x, occupied);
      if (base + occupied <= header.capacity.x) {
        sBase = base;
        atomicMax(header.dispatch.x, min(base + occupied, 65535u));
      } else {
        atomicAdd(header.counts.w, 1u);  // the CPU grows the buffer for the next frame
      }
    }
  }
  barrier();

  const uint tile = gl_WorkGroupID.y * frame.clusterGrid.x + gl_WorkGroupID.x;
  if (inside) pixelClusters[uint(p.y) * uint(frame.viewport.x) + uint(p.x)] = geometry && sBase != kNoCluster ? sBase + rank : kNoCluster;
  // One invocation per occupied cluster writes it; its slice is the rank-th set bit.
  if (local < occupied && sBase != kNoCluster) {
    uint k = 0u, seen = 0u;
    for (uint w = 0u; w < kSliceWords; ++w) {
      uint bits = sSlices[w], n = bitCount(bits);
      if (seen + n > local) {
        for (uint r = local - seen; r > 0u; --r) bits &= bits - 1u;
        k = w * 32u + uint(findLSB(bits));
        break;
      }
      seen += n;
    }
    Cluster c;
    c.lo = vec4(unordered(sLo[local * 3u]), unordered(sLo[local * 3u + 1u]), unordered(sLo[local * 3u + 2u]), 0.0);
    c.hi = vec4(unordered(~sHi[local * 3u]), unordered(~sHi[local * 3u + 1u]), unordered(~sHi[local * 3u + 2u]), 0.0);
    c.info = uvec4(tile, k, 0u, 0u);
    clusters[sBase + local] = c;
  }
  // The bin's box (every surface point of its tiles, clusters that found no room included).
  if (local < occupied) {
    const uint bin = binIndex(tile);
    for (int a = 0; a < 3; ++a) {
      atomicMin(binBoxes[bin * 2u][a], sLo[local * 3u + a]);
      atomicMin(binBoxes[bin * 2u + 1u][a], sHi[local * 3u + a]);
    }
  }
}
