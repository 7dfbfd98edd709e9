#version 430
// Gouraud shading: Phong evaluated per vertex (surface.vert with GOURAUD), its linear colour
// interpolated across the triangle, display-encoded here.
#include "../common/frame.glsl"

in vec3 v_world;
in vec3 v_normal;
in vec3 v_color;
layout(location = 0) out vec4 out_color;

void main() { out_color = vec4(to_display(v_color), 1.0); }
