#version 460
#extension GL_GOOGLE_include_directive : require
// Device check of the point-light formula: shadePoint (shading.h), the function every lighting
// pass calls, run over given surface points and lights (albedo, specular and colour 1). The double
// reference evaluates the same formula; tests compare the two (renderer/readback/shading_probe.h).
#include "shared.h"
#include "shading.h"

layout(local_size_x = 64) in;
// Per case: [0] N, [1] P, [2] light position xyz and radius w; [3] written: the light's rgb.
layout(set = 1, binding = kBindingTileLights, std430) buffer Values { vec4 values[]; };

void main() {
  const uint i = gl_GlobalInvocationID.x * 4u;  // the caller pads the cases to a multiple of 64
  const vec4 l = values[i + 2u];
  values[i + 3u] = vec4(shadePoint(vec3(1.0), 1.0, values[i].xyz, values[i + 1u].xyz, l.xyz, l.w, vec3(1.0)), 0.0);
}
