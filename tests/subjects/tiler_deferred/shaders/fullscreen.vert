#version 450
// tiler_deferred: one triangle covering the viewport (vertices from gl_VertexIndex, no buffers).
void main() {
  const vec2 p = vec2(float((gl_VertexIndex << 1) & 2), float(gl_VertexIndex & 2));
  gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}
