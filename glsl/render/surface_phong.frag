#version 430
// Per-pixel Phong (common/frame.glsl) on the liquid surface, with the normal interpolated across the
// triangle and renormalised. The base colour is surface.vert's kWaterBase.
#include "../common/frame.glsl"

in vec3 v_world;
in vec3 v_normal;
layout(location = 0) out vec4 out_color;

void main() {
    vec3 n = normalize(v_normal);
    vec3 v = normalize(frame.eye.xyz - v_world);
    out_color = vec4(shade_phong(vec3(0.10, 0.35, 0.80), n, v), 1.0);
}
