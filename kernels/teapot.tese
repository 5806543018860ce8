#version 410 core
// Book 3.2 (the thesis's Listing 3.5, done right, errata B11): for each vertex the fixed
// tessellator generates, evaluate the bicubic Bezier patch (book 1.3, eq. 1.4) and its normal
// du x dv (book 1.4) at (u, v) = gl_TessCoord, and project the point with the model-view-
// projection matrix into the vec4 gl_Position. Control point P_ij is patch_point[i + 4 j],
// i running in u (bezier_patch.hpp's layout).
// [listing tese]
layout(quads, equal_spacing, ccw) in;
in vec3 patch_point[];
uniform mat4 mvp;
uniform mat3 normal_to_world;
out vec3 normal;

vec4 bernstein(float t) {
  float s = 1.0 - t;
  return vec4(s * s * s, 3.0 * s * s * t, 3.0 * s * t * t, t * t * t);
}
vec4 bernstein_derivative(float t) {
  float s = 1.0 - t;
  return vec4(-3.0 * s * s, 3.0 * s * s - 6.0 * s * t, 6.0 * s * t - 3.0 * t * t, 3.0 * t * t);
}

// The point and the two tangents at (u, v).
void evaluate(float u, float v, out vec3 p, out vec3 du, out vec3 dv) {
  vec4 bu = bernstein(u), bv = bernstein(v);
  vec4 dbu = bernstein_derivative(u), dbv = bernstein_derivative(v);
  p = vec3(0.0); du = vec3(0.0); dv = vec3(0.0);
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) {
      vec3 P = patch_point[i + 4 * j];
      p += bu[i] * bv[j] * P;
      du += dbu[i] * bv[j] * P;
      dv += bu[i] * dbv[j] * P;
    }
}

void main() {
  vec3 p, du, dv;
  evaluate(gl_TessCoord.x, gl_TessCoord.y, p, du, dv);
  vec3 n = cross(du, dv);
  if (length(n) < 1e-6) {  // a collapsed row (lid knob, bottom): the normal just inside
    vec3 q, du2, dv2;
    evaluate(mix(gl_TessCoord.x, 0.5, 1e-3), mix(gl_TessCoord.y, 0.5, 1e-3), q, du2, dv2);
    n = cross(du2, dv2);
  }
  normal = normal_to_world * n;
  gl_Position = mvp * vec4(p, 1.0);
}
// [end]
