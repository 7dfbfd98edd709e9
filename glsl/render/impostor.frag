#version 430
// Ray-sphere intersection per pixel: exact silhouette, normal and depth, then Phong shading.
// The base colour ramps with speed, or (RANRYU_BY_LEVEL) is the sub-particle level's (impostor.vert).
#include "impostor.glsl"

in vec3 v_view_pos;
flat in vec3 v_center;
flat in float v_speed;
flat in float v_radius;
#ifdef RANRYU_BY_LEVEL
flat in vec3 v_base;
#endif
layout(location = 0) out vec4 out_color;

void main() {
    vec3 dir = normalize(v_view_pos);   // eye ray, view space (the eye is at the origin)
    float t = sphere_front(dir, v_center, v_radius);
    if (t < 0.0) discard;
    vec3 p = t * dir;
    gl_FragDepth = window_depth(p);
#ifdef RANRYU_BY_LEVEL
    vec3 base = v_base;
#else
    vec3 base = speed_base(v_speed);
#endif
    out_color = vec4(shade_impostor(base, p, v_center, v_radius, dir), 1.0);
}
