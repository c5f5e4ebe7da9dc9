#version 460
// One triangle covering the viewport (the view's clipped rectangle): the fragment stage maps
// each framebuffer pixel back to a target texel.
void main() {
  vec2 p = vec2((gl_VertexIndex << 1) & 2, gl_VertexIndex & 2) * 2.0 - 1.0;
  gl_Position = vec4(p, 0.0, 1.0);
}
