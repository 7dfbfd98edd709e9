#version 430
// The tank's four side walls as 8 triangles (24 vertices from gl_VertexID), counter-clockwise seen
// from inside the tank: with back faces culled, only the walls whose inner side faces the eye are
// drawn (the far ones), and the near ones leave the view into the tank open.
#include "../common/frame.glsl"

out vec3 v_world;
out vec3 v_normal;   // the wall's inward normal

// Per wall: the corner (bits x, z of tank_min/max) at its start, its horizontal direction's end
// corner, and its inward normal; the quad spans the tank's height.
const ivec2 kWall[4] = ivec2[4](ivec2(0, 1), ivec2(1, 3), ivec2(3, 2), ivec2(2, 0));   // corners: bit 0 x, bit 1 z
const vec3 kInward[4] = vec3[4](vec3(0.0, 0.0, 1.0), vec3(-1.0, 0.0, 0.0), vec3(0.0, 0.0, -1.0), vec3(1.0, 0.0, 0.0));
// Two triangles of a quad (a = start, b = end; 0 bottom, 1 top), CCW seen along −inward.
const ivec2 kQuad[6] = ivec2[6](ivec2(0, 0), ivec2(1, 0), ivec2(0, 1), ivec2(1, 0), ivec2(1, 1), ivec2(0, 1));

vec3 corner(int c, int top) {
    return vec3((c & 1) != 0 ? frame.tank_max.x : frame.tank_min.x, top != 0 ? frame.tank_max.y : frame.tank_min.y,
                (c & 2) != 0 ? frame.tank_max.z : frame.tank_min.z);
}

void main() {
    int wall = gl_VertexID / 6;
    ivec2 q = kQuad[gl_VertexID % 6];
    v_world = corner(q.x == 0 ? kWall[wall].x : kWall[wall].y, q.y);
    v_normal = kInward[wall];
    gl_Position = frame.view_proj * vec4(v_world, 1.0);
}
