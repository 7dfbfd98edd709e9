#version 430
// A floor quad at the tank's bottom, three tank-sizes wide, from gl_VertexID (4-vertex strip).
#include "../common/frame.glsl"

out vec3 v_world;
out vec3 v_normal;   // +y (tiles.frag reads it)

void main() {
    vec2 corner = vec2(float(gl_VertexID & 1), float(gl_VertexID >> 1));
    vec3 size = frame.tank_max.xyz - frame.tank_min.xyz;
    float margin = max(size.x, size.z);
    vec2 lo = frame.tank_min.xz - margin, hi = frame.tank_max.xz + margin;
    vec2 xz = mix(lo, hi, corner);
    v_world = vec3(xz.x, frame.tank_min.y, xz.y);
    v_normal = vec3(0.0, 1.0, 0.0);
    gl_Position = frame.view_proj * vec4(v_world, 1.0);
}
