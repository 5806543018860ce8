#version 330 core
// One triangle that covers the screen (book 4.3): vertices 0, 1, 2 go to (-1,-1), (3,-1), (-1,3),
// with texture coordinates 0..2, so the visible part is exactly [0,1]^2. No vertex buffer needed.
out vec2 uv;
void main() {
  vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
  uv = p;
  gl_Position = vec4(2.0 * p - 1.0, 0.0, 1.0);
}
