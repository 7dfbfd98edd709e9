#version 430
// The liquid surface: marching cubes' triangles (gpu::MeshVertex, drawn with glDrawArraysIndirect).
// Passes the world position and normal on; with GOURAUD defined it also evaluates Phong here, per
// vertex (Gouraud 1971), for surface_gouraud.frag to interpolate.
#include "../common/frame.glsl"

layout(location = RANRYU_ATTR_MESH_POSITION) in vec4 in_position;
layout(location = RANRYU_ATTR_MESH_NORMAL) in vec4 in_normal;

out vec3 v_world;
out vec3 v_normal;
#ifdef GOURAUD
out vec3 v_color;   // linear Phong at the vertex
#endif

// The surface's base colour (Phong and Gouraud modes).
const vec3 kWaterBase = vec3(0.10, 0.35, 0.80);

void main() {
    v_world = in_position.xyz;
    v_normal = in_normal.xyz;
#ifdef GOURAUD
    v_color = phong_linear(kWaterBase, normalize(in_normal.xyz), normalize(frame.eye.xyz - in_position.xyz));
#endif
    gl_Position = frame.view_proj * vec4(in_position.xyz, 1.0);
}
