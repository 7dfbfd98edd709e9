#version 430
// The liquid's mesh seen from the sun (orthographic, u_shadow_matrix), for shadow_map.frag.
#include "water.glsl"

layout(location = RANRYU_ATTR_MESH_POSITION) in vec4 in_position;

out vec3 v_world;

void main() {
    v_world = in_position.xyz;
    gl_Position = u_shadow_matrix * vec4(in_position.xyz, 1.0);
}
