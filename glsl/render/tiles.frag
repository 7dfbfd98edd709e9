#version 430
// The water mode's floor and tank walls: tiles (R9) inside the tank, plain ground outside its
// footprint, into the opaque scene's target (linear). Built with WALLS for the walls (walls.vert),
// which are tiled everywhere.
//   rgb: the scene cache's C_lit of (R13), the colour (R11) gives with no liquid's shadow; built with
//        SHADOW_INLINE (the redraw path), (R11) with the shadow (R10) itself;
//   a:   the sun's share q of (R13) (0 with SHADOW_INLINE: the shadow is in already). compose.comp
//        applies c = C_lit·(1 − q·(1 − S(x))) at the x the depth holds.
#include "water.glsl"

in vec3 v_world;
in vec3 v_normal;
layout(location = 0) out vec4 out_color;

void main() {
    vec3 n = normalize(v_normal);
    vec2 uv = abs(n.y) > 0.5 ? v_world.xz : (abs(n.x) > 0.5 ? v_world.zy : v_world.xy);
#ifdef WALLS
    vec3 albedo = tile_albedo(uv);
#else
    bool inside = all(greaterThanEqual(v_world.xz, frame.tank_min.xz)) && all(lessThan(v_world.xz, frame.tank_max.xz));
    vec3 albedo = inside ? tile_albedo(uv) : vec3(RANRYU_GROUND_ALBEDO);
#endif
#ifdef SHADOW_INLINE
    out_color = vec4(lit_matte(albedo, n, v_world), 0.0);
#else
    out_color = lit_unshadowed(albedo, n);
#endif
}
