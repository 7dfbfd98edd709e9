#version 430
// The tank's 12 edges as GL_LINES (24 vertices from gl_VertexID).
#include "../common/frame.glsl"

const ivec2 kEdges[12] = ivec2[12](ivec2(0, 1), ivec2(2, 3), ivec2(4, 5), ivec2(6, 7),   // along x
                                   ivec2(0, 2), ivec2(1, 3), ivec2(4, 6), ivec2(5, 7),   // along y
                                   ivec2(0, 4), ivec2(1, 5), ivec2(2, 6), ivec2(3, 7));  // along z

void main() {
    ivec2 e = kEdges[gl_VertexID >> 1];
    int corner = (gl_VertexID & 1) == 0 ? e.x : e.y;   // bit 0: x, bit 1: y, bit 2: z
    vec3 t = vec3(float(corner & 1), float((corner >> 1) & 1), float((corner >> 2) & 1));
    vec3 p = mix(frame.tank_min.xyz, frame.tank_max.xyz, t);
    gl_Position = frame.view_proj * vec4(p, 1.0);
}
