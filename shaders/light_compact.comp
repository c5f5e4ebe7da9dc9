#version 460
#extension GL_GOOGLE_include_directive : require
// Light setup on the GPU, step 2: the visible list in scene-light order (deterministic, whatever
// order invocations run in). Each workgroup sums the visible counts of the groups before it (at
// most a few hundred), and every visible light of its group goes to that base + its place in the
// group, its position and radius to the same place of visiblePositions. The first workgroup writes the totals (LightCounts: visible, culled, the fairies'
// indirect draw).
#define GB_LIGHTS_WRITTEN
#include "common.glsl"

layout(local_size_x = kLightSetupGroup) in;
layout(set = 1, binding = kBindingLightScratch, std430) readonly buffer ScratchBlock { uint scratch[]; };

shared uvec4 sSum[kLightSetupGroup];

void main() {
  const uint n = frame.time64.z, local = gl_LocalInvocationIndex, group = gl_WorkGroupID.x;
  const uint groups = (n + kLightSetupGroup - 1u) / kLightSetupGroup;
  // The first workgroup sums every group (for the totals), the others the groups before them.
  const uint upTo = group == 0u ? groups : group;
  uvec4 sum = uvec4(0u);
  for (uint g = local; g < upTo; g += kLightSetupGroup)
    sum += uvec4(scratch[n + g * 4u], scratch[n + g * 4u + 1u], scratch[n + g * 4u + 2u], scratch[n + g * 4u + 3u]);
  sSum[local] = sum;
  barrier();
  for (uint stride = kLightSetupGroup / 2u; stride > 0u; stride >>= 1) {
    if (local < stride) sSum[local] += sSum[local + stride];
    barrier();
  }
  const uint base = group == 0u ? 0u : sSum[0].x;
  const uint i = gl_GlobalInvocationID.x;
  if (i < n && scratch[i] != 0xFFFFFFFFu) {
    visibleLights[base + scratch[i]] = i;
    visiblePositions[base + scratch[i]] = lights[i].eyePositionRadius;
  }
  if (group == 0u && local == 0u) {
    const uvec4 total = sSum[0];
    lightCounts.counts = total;  // visible, frustum, empty, sub-pixel
    lightCounts.fairyDraw = uvec4(6u, total.x, 0u, 0u);
  }
}
