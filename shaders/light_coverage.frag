#version 460
#extension GL_GOOGLE_include_directive : require
// Full light coverage: counts every light volume covering a pixel in screen space (no tests).
#include "common.glsl"

layout(set = 1, binding = kBindingCoverage, r32ui) uniform uimage2D coverage;
layout(location = 0) flat in uint inLight;

void main() { imageAtomicAdd(coverage, ivec2(gl_FragCoord.xy), 1u); }
