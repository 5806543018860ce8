#version 410 core
// Book 3.2: a headlight-style diffuse shade of the interpolated normal, lit from both sides
// (the teapot's patches do not all wind the same way), or one colour for the wireframe.
in vec3 normal;
uniform int wireframe;
uniform vec3 light;  // unit vector towards the light, in world space
out vec4 frag_colour;

void main() {
  if (wireframe != 0) {
    frag_colour = vec4(0.95, 0.85, 0.4, 1.0);
    return;
  }
  float diffuse = abs(dot(normalize(normal), light));
  frag_colour = vec4(vec3(0.85, 0.55, 0.3) * (0.15 + 0.85 * diffuse), 1.0);
}
