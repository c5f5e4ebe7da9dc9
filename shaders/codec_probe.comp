#version 460
#extension GL_GOOGLE_include_directive : require
// Device check of the G-buffer's normal encoder: encodeNormalShadow (gbuffer_codec.glsl), the
// function the G-buffer pass calls, run over given unit vectors. The values come back as the
// shader writes them (before the attachment's conversion), for the CPU mirror to be tested against.
#include "shared.h"

layout(constant_id = kSpecNormalEncoding) const uint NORMAL_ENCODING = kNormalRgba16f;
layout(constant_id = kSpecOctPrecise) const uint OCT_PRECISE = 0;
#include "gbuffer_codec.glsl"

layout(local_size_x = 64) in;
layout(set = 1, binding = kBindingTileLights, std430) buffer Values { vec4 values[]; };

void main() {
  uint i = gl_GlobalInvocationID.x;  // the caller pads the values to a multiple of 64
  values[i] = encodeNormalShadow(values[i].xyz, 1.0);
}
