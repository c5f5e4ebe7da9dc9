#version 460
#extension GL_GOOGLE_include_directive : require
// One triangle covering the screen at depth `gl_Position.z` = far (sky) or anything (lighting).
#include "common.glsl"

layout(location = 0) out vec2 outNdc;

void main() {
  vec2 p = vec2((gl_VertexIndex << 1) & 2, gl_VertexIndex & 2) * 2.0 - 1.0;
  outNdc = p;
  gl_Position = vec4(p, farDepth(), 1.0);
}
