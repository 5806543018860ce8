#version 330 core
// Book 3.2 (the thesis's Listing 3.2): the interpolated colour, opaque.
// [listing triangle-frag]
in vec3 vertex_colour;
out vec4 frag_colour;

void main() { frag_colour = vec4(vertex_colour, 1.0); }
// [end]
