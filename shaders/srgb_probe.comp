#version 460
#extension GL_GOOGLE_include_directive : require
// Device characterization: what the sampler returns for each 8-bit value of an sRGB texture
// (texel i holds byte i). The lighting passes read albedo_specular through the same path.
#include "shared.h"

layout(local_size_x = 64) in;
layout(set = 1, binding = kBindingAlbedo) uniform sampler2D probe;
layout(set = 1, binding = kBindingTileLights, std430) writeonly buffer Values { vec4 values[]; };

void main() {
  uint i = gl_GlobalInvocationID.x;
  values[i] = texelFetch(probe, ivec2(i, 0), 0);
}
