#version 460
#extension GL_GOOGLE_include_directive : require
// Fairy sprites in compute, step 2 (the fairy_lights raster pass's image, without its fill): one
// workgroup per 16x16 tile lists the sprites of its bin that reach the tile, in visible-list order
// (the draw order), then each pixel blends them over hdr as the raster pass does: depth-tested
// against the depth buffer (closer or equal), the sprite's radial falloff (fairy.frag) at the pixel
// centre, premultiplied "over" in fp32. A tile with more than kFairyListMax sprites reads them from
// the bin instead. The reach tests read only the visible positions. (Placing each listed sprite once
// into shared memory, 32 B each, instead of once per pixel made the pass 3x slower on an H200, even
// at 256 lights; the 24 KiB of shared memory it took is the suspect, not confirmed.)
#include "common.glsl"
#include "fairy_common.glsl"

layout(local_size_x = kTileSize, local_size_y = kTileSize) in;
layout(set = 1, binding = kBindingHdrStorage, GB_HDR_FORMAT) uniform image2D hdr;
layout(set = 1, binding = kBindingDepth) uniform sampler2D hardwareDepth;

const uint kGroup = kTileSize * kTileSize;
shared uint sCount[kGroup];
shared uint sList[kFairyListMax];  // the listed sprites' light indices, in visible-list order
shared uint sTotal;

bool reachesTile(Sprite s, ivec2 t0, ivec2 t1) {
  ivec2 p0, p1;
  spritePixels(s, p0, p1);
  return s.drawn && p0.x <= t1.x && p1.x >= t0.x && p0.y <= t1.y && p1.y >= t0.y;
}

void blend(inout vec4 dst, Sprite s, vec2 centre, float depth) {
  if (!(REVERSED_Z != 0 ? s.depth >= depth : s.depth <= depth)) return;  // depth test
  vec2 local = (centre - s.lo) / (s.hi - s.lo) * 2.0 - 1.0;
  float r2 = dot(local, local);
  if (r2 >= 1.0) return;  // fairy.frag discards
  float a = (1.0 - r2) * (1.0 - r2);
  vec4 src = vec4(s.color * (0.6 + 2.4 * a * a) * a, a);
  dst = src + dst * (1.0 - a);  // blend ONE, ONE_MINUS_SRC_ALPHA for colour and alpha
}

void main() {
  const uint t = gl_LocalInvocationIndex;
  const ivec2 t0 = ivec2(gl_WorkGroupID.xy) * int(kTileSize), t1 = t0 + int(kTileSize) - 1;
  const uint mask = (uint(t0.y) / kBinTile * frame.clusterGrid.z + uint(t0.x) / kBinTile) * frame.clusterGrid.w;
  const uint words = (lightCounts.counts.x + 31u) / 32u;
  const uint per = (words + kGroup - 1u) / kGroup;
  const uint w0 = min(t * per, words), w1 = min(w0 + per, words);
  uint n = 0u;
  for (uint w = w0; w < w1; ++w)
    for (uint bits = fairyBits[mask + w]; bits != 0u; bits &= bits - 1u)
      n += reachesTile(spriteAt(visiblePositions[w * 32u + uint(findLSB(bits))], vec3(0.0)), t0, t1) ? 1u : 0u;
  sCount[t] = n;
  barrier();
  if (t == 0u) {
    uint sum = 0u;
    for (uint i = 0u; i < kGroup; ++i) {
      uint c = sCount[i];
      sCount[i] = sum;
      sum += c;
    }
    sTotal = sum;
  }
  barrier();
  const bool listed = sTotal <= kFairyListMax;
  if (listed) {
    uint at = sCount[t];
    for (uint w = w0; w < w1; ++w)
      for (uint bits = fairyBits[mask + w]; bits != 0u; bits &= bits - 1u) {
        const uint v = w * 32u + uint(findLSB(bits));
        if (reachesTile(spriteAt(visiblePositions[v], vec3(0.0)), t0, t1)) sList[at++] = visibleLights[v];
      }
  }
  barrier();
  const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (sTotal == 0u || p.x >= int(frame.viewport.x) || p.y >= int(frame.viewport.y)) return;
  const vec2 centre = vec2(p) + 0.5;
  const float depth = texelFetch(hardwareDepth, p, 0).r;
  vec4 c = imageLoad(hdr, p);
  if (listed) {
    for (uint i = 0u; i < sTotal; ++i) blend(c, sprite(lights[sList[i]]), centre, depth);
  } else {
    for (uint w = 0u; w < words; ++w)
      for (uint bits = fairyBits[mask + w]; bits != 0u; bits &= bits - 1u)
        blend(c, sprite(lights[visibleLights[w * 32u + uint(findLSB(bits))]]), centre, depth);
  }
  imageStore(hdr, p, c);
}
