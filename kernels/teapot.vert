#version 410 core
// Book 3.2, tessellation: the vertex shader only hands the control points on; the patch is
// evaluated in the TES (teapot.tese).
layout(location = 0) in vec3 position;
out vec3 control_point;

void main() { control_point = position; }
