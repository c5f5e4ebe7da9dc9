#version 460
#extension GL_GOOGLE_include_directive : require
// Clustered shading, step 2 (light assignment, coarse): one invocation per visible light. The
// light's sphere is tested against the box of the surface points of every 64x64-pixel bin its
// screen rectangle touches, and sets its bit (its visible-list position) in each bin it reaches.
// Bits make the result independent of the order invocations run in.
#include "common.glsl"
#include "cluster_common.glsl"

layout(local_size_x = 64) in;

// Conservative pixel rectangle of a sphere wholly in front of the near plane: the projections of
// its eye-space box's corners bound the projection of the box (convex, in front of the eye),
// which holds the sphere's. Widened by 2 pixels for rounding.
void screenRect(vec4 l, out vec2 lo, out vec2 hi) {
  lo = vec2(1e30);
  hi = vec2(-1e30);
  for (int k = 0; k < 8; ++k) {
    vec3 q = l.xyz + vec3((k & 1) != 0 ? l.w : -l.w, (k & 2) != 0 ? l.w : -l.w, (k & 4) != 0 ? l.w : -l.w);
    vec4 clip = frame.clipFromEye * vec4(q, 1.0);
    vec2 px = (clip.xy / clip.w * 0.5 + 0.5) * frame.viewport.xy;
    lo = min(lo, px);
    hi = max(hi, px);
  }
  lo -= 2.0;
  hi += 2.0;
}

void main() {
  const uint v = gl_GlobalInvocationID.x;
  if (v >= lightCounts.counts.x) return;
  const vec4 l = visiblePositions[v];
  const uint binsX = frame.clusterGrid.z;
  const uint binsY = (uint(frame.viewport.y) + kBinTile - 1u) / kBinTile;
  uvec2 b0 = uvec2(0u), b1 = uvec2(binsX - 1u, binsY - 1u);
  // A box reaching the eye plane (or close to it) projects without bound: the whole screen.
  if (-l.z - l.w > 1e-3 * max(abs(l.z), 1e-3)) {
    vec2 lo, hi;
    screenRect(l, lo, hi);
    if (hi.x < 0.0 || hi.y < 0.0 || lo.x >= frame.viewport.x || lo.y >= frame.viewport.y) return;
    b0 = uvec2(clamp(lo, vec2(0.0), frame.viewport.xy - 1.0)) / kBinTile;
    b1 = uvec2(clamp(hi, vec2(0.0), frame.viewport.xy - 1.0)) / kBinTile;
  }
  const uint word = v >> 5, bit = 1u << (v & 31u);
  for (uint y = b0.y; y <= b1.y; ++y)
    for (uint x = b0.x; x <= b1.x; ++x) {
      const uint bin = y * binsX + x;
      const uvec4 lo = binBoxes[bin * 2u], nhi = binBoxes[bin * 2u + 1u];
      if (lo.x == 0xFFFFFFFFu) continue;  // no surface point in the bin
      vec3 boxLo = vec3(unordered(lo.x), unordered(lo.y), unordered(lo.z));
      vec3 boxHi = vec3(unordered(~nhi.x), unordered(~nhi.y), unordered(~nhi.z));
      if (sphereReachesBox(l, boxLo, boxHi)) atomicOr(binBits[bin * frame.clusterGrid.w + word], bit);
    }
}
