#version 410 core
// Book 3.2 (the thesis's Listing 3.4, with gl_TessLevelOuter spelt right, errata B11): a patch
// of 16 control points in and out, and the levels for the quad domain. Outer edges 0 and 2 take
// outer.x, edges 1 and 3 take outer.y; the inner levels are inner.x and inner.y.
// [listing tesc]
layout(vertices = 16) out;
in vec3 control_point[];
out vec3 patch_point[];
uniform vec2 outer;
uniform vec2 inner;

void main() {
  patch_point[gl_InvocationID] = control_point[gl_InvocationID];
  if (gl_InvocationID == 0) {  // the levels are per patch: one invocation sets them
    gl_TessLevelOuter[0] = outer.x;
    gl_TessLevelOuter[1] = outer.y;
    gl_TessLevelOuter[2] = outer.x;
    gl_TessLevelOuter[3] = outer.y;
    gl_TessLevelInner[0] = inner.x;
    gl_TessLevelInner[1] = inner.y;
  }
}
// [end]
