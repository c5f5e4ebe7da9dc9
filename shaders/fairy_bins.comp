#version 460
#extension GL_GOOGLE_include_directive : require
// Fairy sprites in compute, step 1: one invocation per visible light sets its bit (its place in
// the visible list) in each 64x64-pixel bin its sprite's pixel rectangle touches. Sprites clipped
// by the near or far plane, or off screen, set none.
#include "common.glsl"
#include "fairy_common.glsl"

layout(local_size_x = 64) in;

void main() {
  const uint v = gl_GlobalInvocationID.x;
  if (v >= lightCounts.counts.x) return;
  const Sprite s = sprite(lights[visibleLights[v]]);
  if (!s.drawn) return;
  ivec2 p0, p1;
  spritePixels(s, p0, p1);
  const ivec2 size = ivec2(frame.viewport.xy);
  if (p1.x < 0 || p1.y < 0 || p0.x >= size.x || p0.y >= size.y) return;
  const uvec2 b0 = uvec2(clamp(p0, ivec2(0), size - 1)) / kBinTile, b1 = uvec2(clamp(p1, ivec2(0), size - 1)) / kBinTile;
  const uint word = v >> 5, bit = 1u << (v & 31u);
  for (uint y = b0.y; y <= b1.y; ++y)
    for (uint x = b0.x; x <= b1.x; ++x) atomicOr(fairyBits[(y * frame.clusterGrid.z + x) * frame.clusterGrid.w + word], bit);
}
