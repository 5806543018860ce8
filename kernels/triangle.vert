#version 330 core
// Book 3.2 (the thesis's Listing 3.1): position at location 0, colour at location 1, the
// locations glVertexAttribPointer's first argument names.
// [listing triangle-vert]
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 colour;
out vec3 vertex_colour;

void main() {
  gl_Position = vec4(position, 1.0);
  vertex_colour = colour;  // interpolated over the triangle for the fragment shader
}
// [end]
