#version 330 core
// Book 3.2 (the thesis's Listing 3.3): a geometry shader receives a whole primitive, here one
// point, and may emit other primitives: each point becomes a short horizontal line, 0.1 to
// either side in normalised device coordinates.
// [listing geom]
layout(points) in;
layout(line_strip, max_vertices = 2) out;
in vec3 vertex_colour[];  // one entry per vertex of the input primitive
out vec3 line_colour;

void main() {
  line_colour = vertex_colour[0];
  gl_Position = gl_in[0].gl_Position + vec4(-0.1, 0.0, 0.0, 0.0);
  EmitVertex();
  line_colour = vertex_colour[0];  // outputs are undefined after EmitVertex: set them again
  gl_Position = gl_in[0].gl_Position + vec4(0.1, 0.0, 0.0, 0.0);
  EmitVertex();
  EndPrimitive();
}
// [end]
