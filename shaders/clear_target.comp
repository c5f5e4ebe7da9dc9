#version 460
#extension GL_GOOGLE_include_directive : require
// clear_gbuffer: zero one G-buffer target through its unsigned storage view of the same texel
// size (r32ui, rg32ui or rgba32ui: GB_CLEAR_FORMAT); zero bits are 0 in every G-buffer format.
#include "shared.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = kSetPass, binding = kBindingClearTarget, GB_CLEAR_FORMAT) uniform writeonly uimage2D target;

void main() {
  const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, imageSize(target)))) return;
  imageStore(target, p, uvec4(0u));
}
