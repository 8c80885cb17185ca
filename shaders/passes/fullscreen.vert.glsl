// One triangle covering the viewport (no vertex buffer), on the reversed-Z far plane (clip z = 0,
// stored depth 0): the viewer's display pass and the G-buffer's background.
void main() {
  vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
  gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}
