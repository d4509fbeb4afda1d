#version 330 core
// A full-screen triangle; v runs from 0 at the bottom to 1 at the top of the viewport.

out float v;

void main() {
  vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);
  v = p.y;
  gl_Position = vec4(2.0 * p - 1.0, 0.0, 1.0);
}
