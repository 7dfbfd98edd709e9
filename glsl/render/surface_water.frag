#version 430
// Water (docs/RENDERING.md): the liquid's front faces over the opaque scene, per pixel,
//   n = normalize(interpolated normal), v = unit vector to the eye
//   R = fresnel_schlick(n·v, n_air, n_water)                                         (R1)
//   reflected = sky(reflect(−v, n)), the sky with its sun (common/frame.glsl)        (R2)
//   highlight = k_s·max(n·h, 0)^α·L, h = normalize(l + v), where n·l > 0             (R4)
//   d = the liquid's thickness along this pixel's ray (liquid_thickness.frag; drawn at
//     1/THICKNESS_DIVISOR of the frame's size, defined by the renderer, and upsampled here)  (R5)
//   refracted: t = refract(−v, n, n_air / n_water); the opaque scene is looked up where the point
//     x + d·t projects (screen-space refraction), or straight behind where that point is off screen
//     or the scene there is nearer than x                                             (R5)
//   T = exp(−σ_a·d), Beer-Lambert                                                    (R6)
//   colour = to_display(R·reflected + (1 − R)·T·behind + highlight)                   (R7)
#include "water.glsl"

in vec3 v_world;
in vec3 v_normal;
layout(location = 0) out vec4 out_color;

void main() {
    vec3 n = normalize(v_normal);
    vec3 v = normalize(frame.eye.xyz - v_world);
    if (dot(n, v) < 0.0) n = -n;   // an interpolated normal may turn away near the silhouette
    float r = fresnel_schlick(dot(n, v), RANRYU_IOR_AIR, RANRYU_IOR_WATER);
    vec3 reflected = sky(reflect(-v, n));

    vec3 l = frame.light_dir.xyz;
    vec3 h = normalize(l + v);
    float highlight = dot(n, l) > 0.0 ? RANRYU_WATER_SPECULAR * pow(max(dot(n, h), 0.0), RANRYU_WATER_SHININESS) : 0.0;

#if THICKNESS_DIVISOR == 1
    float d = max(texelFetch(t_thickness, ivec2(gl_FragCoord.xy), 0).r, 0.0);
#else
    // Upsampled bilinearly: the frame's position x_w lies at x_w / THICKNESS_DIVISOR in its texels.
    vec2 at = gl_FragCoord.xy / (float(THICKNESS_DIVISOR) * vec2(textureSize(t_thickness, 0)));
    float d = max(texture(t_thickness, at).r, 0.0);
#endif
    vec3 t = refract(-v, n, RANRYU_IOR_AIR / RANRYU_IOR_WATER);
    vec4 clip = frame.view_proj * vec4(v_world + d * t, 1.0);
    vec2 uv = (clip.xy / clip.w) * 0.5 + 0.5;
    vec2 straight = gl_FragCoord.xy * frame.viewport.zw;
    if (clip.w <= 0.0 || any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0)))) {
        uv = straight;
    } else {
        vec2 q = uv * frame.viewport.xy;
        float t_scene = eye_distance(q, texelFetch(t_scene_depth, ivec2(q), 0).r);
        if (t_scene < length(frame.eye.xyz - v_world)) uv = straight;
    }
    vec3 behind = texture(t_scene_color, uv).rgb;
    vec3 transmitted = exp(-u_absorption.rgb * d);
    vec3 c = r * reflected + (1.0 - r) * transmitted * behind + highlight * frame.light_color.rgb;
    out_color = vec4(to_display(c), 1.0);
}
