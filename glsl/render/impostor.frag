#version 430
// Ray-sphere intersection per pixel: exact silhouette, normal and depth, then Phong shading.
// The base colour ramps with speed, or (RANRYU_BY_LEVEL) is the sub-particle level's (impostor.vert).
#include "../common/frame.glsl"

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
    float r = v_radius;
    // |t·dir − c|² = r²  ⇒  t = dir·c − sqrt((dir·c)² − |c|² + r²)
    float b = dot(dir, v_center);
    float disc = b * b - dot(v_center, v_center) + r * r;
    if (disc < 0.0) discard;
    float t = b - sqrt(disc);
    vec3 p = t * dir;
    vec4 clip = frame.proj * vec4(p, 1.0);
    gl_FragDepth = 0.5 * (clip.z / clip.w) + 0.5;

    mat3 to_world = transpose(mat3(frame.view));   // the view matrix is rigid
    vec3 n = to_world * ((p - v_center) / r);
    vec3 v = -(to_world * dir);
#ifdef RANRYU_BY_LEVEL
    vec3 base = v_base;
#else
    float s = clamp(v_speed / max(frame.speed_scale.x, 1e-6), 0.0, 1.0);
    vec3 base = mix(vec3(0.10, 0.35, 0.80), vec3(0.85, 0.95, 1.00), s);
#endif
    out_color = vec4(shade_phong(base, normalize(n), normalize(v)), 1.0);
}
