#version 460
#extension GL_GOOGLE_include_directive : require
// Sky: a procedural gradient by world-space view direction, only where no geometry was drawn
// (deferred and forward; tiled and clustered write it from their compute pass).
#include "common.glsl"
#include "sky.glsl"

layout(location = 0) in vec2 inNdc;
layout(location = 0) out vec4 outColor;

void main() { outColor = vec4(skyColor(inNdc), 1.0); }
