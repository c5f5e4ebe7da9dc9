// Clustered shading's buffers and helpers, shared by the cluster passes (renderer/passes/clustered.cpp).
layout(set = 1, binding = kBindingClusterHeader, std430) coherent buffer HeaderBlock { ClusterHeader header; };
layout(set = 1, binding = kBindingClusters, std430) buffer ClusterBlock { Cluster clusters[]; };
layout(set = 1, binding = kBindingPixelClusters, std430) buffer PixelClusterBlock { uint pixelClusters[]; };
layout(set = 1, binding = kBindingLightLists, std430) buffer ListBlock { uint lightLists[]; };
layout(set = 1, binding = kBindingBinBits, std430) buffer BinBitsBlock { uint binBits[]; };
// Per bin: [0] ordered(lo.xyz), [1] ~ordered(hi.xyz), both atomicMin'd (one fill value clears both).
layout(set = 1, binding = kBindingBinBoxes, std430) buffer BinBoxBlock { uvec4 binBoxes[]; };

// Float <-> uint with the same order (atomicMin/Max on signed floats).
uint ordered(float f) {
  uint b = floatBitsToUint(f);
  return (b & 0x80000000u) != 0u ? ~b : b | 0x80000000u;
}
float unordered(uint u) { return uintBitsToFloat((u & 0x80000000u) != 0u ? u & 0x7FFFFFFFu : ~u); }

// Exponential depth slice of an eye-space point (eye depth -P.z > 0).
uint depthSlice(vec3 P) {
  float k = floor(log2(max(-P.z, 1e-30)) * frame.clusterSlices.x + frame.clusterSlices.y);
  return uint(clamp(k, 0.0, float(kClusterMaxSlices - 1u)));
}

// The light reaches the box when the box's nearest point to its centre is inside its radius. A
// surface point inside the sphere is inside the box, so nothing that lights a pixel is dropped;
// the relative margin covers rounding of the box distance (and of P between shader modules).
bool sphereReachesBox(vec4 light, vec3 lo, vec3 hi) {
  vec3 d = max(max(lo - light.xyz, light.xyz - hi), 0.0);
  return dot(d, d) < light.w * light.w * 1.0001;
}

uint binIndex(uint tile) {
  uint tilesPerBin = kBinTile / kClusterTile;
  uint tx = tile % frame.clusterGrid.x, ty = tile / frame.clusterGrid.x;
  return (ty / tilesPerBin) * frame.clusterGrid.z + tx / tilesPerBin;
}
