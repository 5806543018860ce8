#version 330 core
// Book 3.2: the colour the geometry shader (points.geom) gave the line.
in vec3 line_colour;
out vec4 frag_colour;

void main() { frag_colour = vec4(line_colour, 1.0); }
