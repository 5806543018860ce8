#version 330 core
// Deliberately broken (chapter 3.2's smoke test): a vec3 assigned to the vec4 output, the same
// type error as the thesis's Listing 3.5 (errata B11).
in vec3 vertex_colour;
out vec4 frag_colour;

void main() { frag_colour = vertex_colour; }
