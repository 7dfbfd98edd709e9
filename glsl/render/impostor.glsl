// A particle drawn as a sphere impostor (docs/RENDERING.md (R15)): the geometry and shading that the
// draw (impostor.vert, impostor.frag) and the compute raster (rasterise_impostors.comp,
// shade_impostors.frag) share, in view space, where the eye is at the origin looking down −z.
#include "../common/frame.glsl"

// The eye ray through window position `frag` (pixels; a pixel's centre at +½), unit, view space:
// the point of z = −1 whose clip x, y over w are the normalised device coordinates of `frag`.
vec3 view_ray(vec2 frag) {
    vec2 ndc = frag * frame.viewport.zw * 2.0 - 1.0;
    return normalize(vec3((ndc.x + frame.proj[2][0]) / frame.proj[0][0], (ndc.y + frame.proj[2][1]) / frame.proj[1][1], -1.0));
}

// The distance along the unit ray `dir` from the eye to the front of the sphere (c, r):
//     |t·dir − c|² = r²  ⇒  t = dir·c − sqrt((dir·c)² − |c|² + r²),
// or −1 where the ray misses it. Positive wherever it hits while the eye is outside (|c| > r).
float sphere_front(vec3 dir, vec3 c, float r) {
    float b = dot(dir, c);
    float disc = b * b - dot(c, c) + r * r;
    return disc < 0.0 ? -1.0 : b - sqrt(disc);
}

// The depth buffer's value of view-space point p: 0.5·z_ndc + 0.5.
float window_depth(vec3 p) {
    vec4 clip = frame.proj * vec4(p, 1.0);
    return 0.5 * (clip.z / clip.w) + 0.5;
}

// The near plane's distance, from the projection (glm::perspective: P[2][2] = −(f + n)/(f − n),
// P[3][2] = −2fn/(f − n)).
float near_plane() { return frame.proj[3][2] / (frame.proj[2][2] - 1.0); }

// The base colour of a particle moving at `speed`: the ramp from slow blue to fast white.
vec3 speed_base(float speed) {
    float s = clamp(speed / max(frame.speed_scale.x, 1e-6), 0.0, 1.0);
    return mix(vec3(0.10, 0.35, 0.80), vec3(0.85, 0.95, 1.00), s);
}

// The base colour of a sub-particle of level E (0: a particle not split), whose radius is r/2^E
// (drawing by level: turbulence/subparticles.h).
vec3 level_base(uint level) {
    const vec3 kLevelColor[4] = vec3[4](vec3(RANRYU_LEVEL_COLOR_0), vec3(RANRYU_LEVEL_COLOR_1), vec3(RANRYU_LEVEL_COLOR_2),
                                        vec3(RANRYU_LEVEL_COLOR_3));
    return kLevelColor[min(level, 3u)];
}

// Phong (frame.glsl) of the sphere (c, r) at its point p seen along `dir`, in world space (the view
// matrix is rigid: its inverse rotation is its transpose), display-encoded.
vec3 shade_impostor(vec3 base, vec3 p, vec3 c, float r, vec3 dir) {
    mat3 to_world = transpose(mat3(frame.view));
    vec3 n = to_world * ((p - c) / r);
    vec3 v = -(to_world * dir);
    return shade_phong(base, normalize(n), normalize(v));
}

// Corner `corner` (±1, ±1) of the quad that covers the sphere (c, r)'s silhouette exactly, |c| > r:
// the quad lies in the plane through c perpendicular to the eye ray, where the silhouette cone of the
// sphere at distance d = |c| has radius r·d / sqrt(d² − r²).
vec3 silhouette_corner(vec3 c, float r, vec2 corner) {
    float d = length(c);
    vec3 axis = c / d;
    vec3 side = normalize(abs(axis.y) < 0.99 ? cross(axis, vec3(0.0, 1.0, 0.0)) : cross(axis, vec3(1.0, 0.0, 0.0)));
    vec3 up = cross(side, axis);
    float extent = r * d / sqrt(d * d - r * r);
    return c + extent * (corner.x * side + corner.y * up);
}
