#version 430
// A 0.1 m checkerboard (floor_albedo, common/frame.glsl), Phong-lit with the normal +y.
#include "../common/frame.glsl"

in vec3 v_world;
layout(location = 0) out vec4 out_color;

void main() {
    vec3 v = normalize(frame.eye.xyz - v_world);
    out_color = vec4(shade_phong(floor_albedo(v_world.xz), vec3(0.0, 1.0, 0.0), v), 1.0);
}
