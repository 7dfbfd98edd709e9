#version 430
// The liquid's mesh (gpu::MeshVertex, glDrawArraysIndirect) by its positions alone, for the passes
// that need no normal: seen from the eye (liquid_thickness.frag) or, built with SUN_VIEW, from the
// sun (orthographic, u_shadow_matrix; shadow_map.frag). docs/RENDERING.md (R5), (R8).
#include "water.glsl"

layout(location = RANRYU_ATTR_MESH_POSITION) in vec4 in_position;

out vec3 v_world;

void main() {
    v_world = in_position.xyz;
#ifdef SUN_VIEW
    gl_Position = u_shadow_matrix * vec4(in_position.xyz, 1.0);
#else
    gl_Position = frame.view_proj * vec4(in_position.xyz, 1.0);
#endif
}
