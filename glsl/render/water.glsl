// The water mode's shared pieces (Shading::water, engine/render/renderer.h): the sun's shadow of the
// liquid, the tiled floor and walls, and the eye distance behind a pixel. Equation numbers are those
// of docs/RENDERING.md.
#include "../common/frame.glsl"

layout(location = RANRYU_LOC_ABSORPTION) uniform vec4 u_absorption;       // rgb: sigma_a (1/m)
layout(location = RANRYU_LOC_SHADOW_MATRIX) uniform mat4 u_shadow_matrix;  // world -> the sun's clip space
layout(location = RANRYU_LOC_SHADOW_ORIGIN) uniform vec4 u_shadow_origin;  // xyz: where s = 0

layout(binding = RANRYU_TEX_SCENE_COLOR) uniform sampler2D t_scene_color;
layout(binding = RANRYU_TEX_SCENE_DEPTH) uniform sampler2D t_scene_depth;
layout(binding = RANRYU_TEX_THICKNESS) uniform sampler2D t_thickness;
layout(binding = RANRYU_TEX_SHADOW_NEAR) uniform sampler2D t_shadow_near;
layout(binding = RANRYU_TEX_SHADOW_THICKNESS) uniform sampler2D t_shadow_thickness;

// (R8) The sun depth: distance along the sunlight's travel, s(x) = (x − o)·(−l).
float sun_depth(vec3 x) { return dot(x - u_shadow_origin.xyz, -frame.light_dir.xyz); }

// (R10) The fraction of sunlight reaching x, per channel: over the (2r + 1)² shadow-map texels around
// x's, 1 where x is no deeper than the liquid nearest the sun (s(x) ≤ s_near + bias), else the
// Beer-Lambert transmittance exp(−σ_a·d_sun) of the liquid's thickness d_sun along the sunlight; averaged.
vec3 sun_transmittance(vec3 x) {
    vec2 uv = (u_shadow_matrix * vec4(x, 1.0)).xy * 0.5 + 0.5;   // orthographic: w = 1
    ivec2 size = textureSize(t_shadow_near, 0);
    ivec2 base = ivec2(floor(uv * vec2(size)));
    float s = sun_depth(x);
    vec3 sum = vec3(0.0);
    for (int dy = -RANRYU_SHADOW_PCF_RADIUS; dy <= RANRYU_SHADOW_PCF_RADIUS; ++dy)
        for (int dx = -RANRYU_SHADOW_PCF_RADIUS; dx <= RANRYU_SHADOW_PCF_RADIUS; ++dx) {
            ivec2 p = base + ivec2(dx, dy);
            if (any(lessThan(p, ivec2(0))) || any(greaterThanEqual(p, size))) {
                sum += vec3(1.0);
                continue;
            }
            float s_near = texelFetch(t_shadow_near, p, 0).r;
            float d = max(texelFetch(t_shadow_thickness, p, 0).r, 0.0);
            sum += s > s_near + RANRYU_SHADOW_BIAS ? exp(-u_absorption.rgb * d) : vec3(1.0);
        }
    const float taps = float((2 * RANRYU_SHADOW_PCF_RADIUS + 1) * (2 * RANRYU_SHADOW_PCF_RADIUS + 1));
    return sum / taps;
}

// (R10) A layer's share of the sunlight's path inside the liquid: −s where the face is toward the sun
// (the light enters), +s where it is away (it leaves). Summed over a closed mesh: d_sun.
float signed_sun_depth(vec3 x, bool front) {
    float s = sun_depth(x);
    return front ? -s : s;
}

// (R9) Tile albedo at the plane coordinates uv (m): grout along each tile's lower edges.
vec3 tile_albedo(vec2 uv) {
    vec2 f = uv / RANRYU_TILE_SIZE - floor(uv / RANRYU_TILE_SIZE);
    const float g = RANRYU_GROUT_WIDTH / RANRYU_TILE_SIZE;
    return any(lessThan(f, vec2(g))) ? vec3(RANRYU_GROUT_ALBEDO) : vec3(RANRYU_TILE_ALBEDO);
}

// (R11) A matte surface lit by the sky's ambient and the sun through the liquid, linear:
//     c = L·albedo·(k_a + k_d·max(n·l, 0)·S(x)),   S of (R10).
vec3 lit_matte(vec3 albedo, vec3 n, vec3 x) {
    float ndl = max(dot(n, frame.light_dir.xyz), 0.0);
    vec3 sun = ndl > 0.0 ? sun_transmittance(x) : vec3(0.0);
    return frame.light_color.rgb * albedo * (frame.light_color.a + frame.material.x * ndl * sun);
}

// (R13) The scene cache's split of (R11) into what the liquid does not change and what it does:
//     c = C_lit·(1 − q·(1 − S(x))),   C_lit = L·albedo·(k_a + k_d·max(n·l, 0)),
//     q = k_d·max(n·l, 0) / (k_a + k_d·max(n·l, 0))   (0 where both terms are 0),
// C_lit the colour (R11) gives with S = 1 and q the sun's share of it. Returns (C_lit, q).
vec4 lit_unshadowed(vec3 albedo, vec3 n) {
    float sun = frame.material.x * max(dot(n, frame.light_dir.xyz), 0.0), all_light = frame.light_color.a + sun;
    return vec4(frame.light_color.rgb * albedo * all_light, all_light > 0.0 ? sun / all_light : 0.0);
}

// (R12) The eye distance of what the depth buffer holds at window position `frag` (pixels) with
// depth value `depth`: the view depth −z = P[3][2] / (z_ndc + P[2][2]) times the length of the
// pixel's view ray (x_ndc / P[0][0], y_ndc / P[1][1], −1).
float eye_distance(vec2 frag, float depth) {
    float view_z = frame.proj[3][2] / ((2.0 * depth - 1.0) + frame.proj[2][2]);
    vec2 ndc = frag * frame.viewport.zw * 2.0 - 1.0;
    return view_z * length(vec3(ndc.x / frame.proj[0][0], ndc.y / frame.proj[1][1], -1.0));
}

// (R12) The world point the depth buffer holds at window position `frag`: the eye plus the eye
// distance along the pixel's view ray, turned into world space (the view matrix is rigid).
vec3 world_position(vec2 frag, float depth) {
    vec2 ndc = frag * frame.viewport.zw * 2.0 - 1.0;
    vec3 ray = transpose(mat3(frame.view)) * vec3(ndc.x / frame.proj[0][0], ndc.y / frame.proj[1][1], -1.0);
    return frame.eye.xyz + eye_distance(frag, depth) * normalize(ray);
}

#ifdef THICKNESS_DIVISOR
// (R5), (R12) The eye distance of the opaque scene behind the centre `at` (window coordinates) of a
// pixel of the thickness target, 1/THICKNESS_DIVISOR of the frame's size: that centre is the centre
// of a THICKNESS_DIVISOR² block of the frame's pixels, and the mean of their depths is the opaque
// plane's depth there (window depth is affine in x_w, y_w over a plane).
float opaque_distance(vec2 at) {
    vec2 frag = at * float(THICKNESS_DIVISOR);   // in the frame's pixels
    ivec2 first = ivec2(at) * THICKNESS_DIVISOR, last = textureSize(t_scene_depth, 0) - 1;
    float depth = 0.0;
    for (int j = 0; j < THICKNESS_DIVISOR; ++j)
        for (int i = 0; i < THICKNESS_DIVISOR; ++i) depth += texelFetch(t_scene_depth, min(first + ivec2(i, j), last), 0).r;
    return eye_distance(frag, depth / float(THICKNESS_DIVISOR * THICKNESS_DIVISOR));
}

// (R5) A layer's share of the thickness at the thickness target's pixel centre `at`: −t on front
// faces, +t on back faces, t = min(|x − eye|, t_opaque). Summed over a closed mesh: the length of
// the view ray inside the liquid in front of the opaque scene.
float signed_eye_distance(vec3 x, vec2 at, bool front) {
    float t = min(length(x - frame.eye.xyz), opaque_distance(at));
    return front ? -t : t;
}
#endif
