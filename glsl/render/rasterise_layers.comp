#version 430
// Every layer of the liquid's mesh rasterised without the raster hardware (docs/RENDERING.md (R14)):
// "shadow-map" when built with SUN_VIEW (the sun's orthographic view, u_shadow_matrix), else
// "liquid-thickness" (the eye's view, frame.view_proj, at 1/THICKNESS_DIVISOR of the frame's size).
// Two dispatches, both indirect:
//   - one invocation per triangle, raster.w triangles (size_raster.comp) of the mesh (gpu::MeshVertex[],
//     three consecutive vertices a triangle, counter-clockwise seen from outside). A triangle over more
//     than RANRYU_RASTER_LARGE_PIXELS pixels is listed in RasterLarge instead (while there is room);
//   - built with LARGE_TRIANGLES: RANRYU_RASTER_LARGE_TILES workgroups per listed triangle, whose
//     invocations share its pixels.
// A triangle is clipped in clip space to −w ≤ z ≤ w, as the GL draw is, and to the guard band
// |x|, |y| ≤ RANRYU_RASTER_GUARD·w (only where a vertex lies outside them), its window coordinates
// snapped to 1/2^RANRYU_RASTER_SUBPIXEL_BITS pixel. Edge functions are exact: integers held in doubles,
// below 2^51 (R14). A pixel is covered when its centre (+0.5) is strictly inside every edge, or on an
// edge that is top or left (the top-left rule: a centre on an edge shared by two triangles is counted
// once). Facing is the sign of the window-space area, as gl_FrontFacing (counter-clockwise, y up);
// degenerate triangles are skipped. The world position is interpolated perspective-correctly at the
// pixel centre from the unsnapped window coordinates (a GL draw may interpolate from the snapped ones:
// the two differ by at most √2/512 pixel of position, R14), and each covered pixel gets, by atomics on
// the R32F targets bound as 32-bit integer images:
//   SUN_VIEW: u_near = min ordered_bits(s) (R8);  u_sum += fixed(signed_sun_depth)    (R10)
//   else:     u_sum += fixed(signed_eye_distance), clipped to the opaque scene         (R5)
// fixed(v) = round(v·2^20): any order of the adds gives the same sum (mod 2^32), exact for |Σ| < 2^11 m.
// decode_raster.comp turns the targets into the floats the draw path leaves.
#include "water.glsl"
#include "../surface/ordered_float.glsl"
#include "../surface/dispatch_2d.glsl"

layout(local_size_x = 64) in;
layout(std430) readonly buffer MeshVertices { MeshVertex vertices[]; };
layout(std430) readonly buffer RasterDispatch { uvec4 raster; };   // w: triangles
// The large triangles of each view (0 the sun's, 1 the eye's): large[v].x listed (the second
// dispatch's workgroups along x), .w claimed; their indices at large_triangles[v·capacity + k].
layout(std430) buffer RasterLarge {
    uvec4 large[2];
    uint large_triangles[];
};
layout(binding = RANRYU_IMG_RASTER_SUM, r32i) uniform iimage2D u_sum;
#ifdef SUN_VIEW
layout(binding = RANRYU_IMG_RASTER_NEAR, r32ui) uniform uimage2D u_near;
const uint kView = 0u;
#else
const uint kView = 1u;
#endif

const double kSubpixel = double(1 << RANRYU_RASTER_SUBPIXEL_BITS);
const float kLargest = 2047.0;   // |v| of one layer: its fixed(v) stays within int

// The clip planes, a·c ≥ 0 inside: near, far, and the guard band on x and y.
const vec4 kPlanes[6] = vec4[](vec4(0.0, 0.0, 1.0, 1.0), vec4(0.0, 0.0, -1.0, 1.0), vec4(-1.0, 0.0, 0.0, RANRYU_RASTER_GUARD),
                               vec4(1.0, 0.0, 0.0, RANRYU_RASTER_GUARD), vec4(0.0, -1.0, 0.0, RANRYU_RASTER_GUARD),
                               vec4(0.0, 1.0, 0.0, RANRYU_RASTER_GUARD));

struct ClipVertex {
    vec4 c;   // clip space
    vec3 x;   // world
};

int fixed_point(float v) { return int(floor(clamp(v, -kLargest, kLargest) * RANRYU_RASTER_FIXED_SCALE + 0.5)); }

double edge(dvec2 a, dvec2 b, dvec2 q) { return (b.x - a.x) * (q.y - a.y) - (b.y - a.y) * (q.x - a.x); }
float edge_f(vec2 a, vec2 b, vec2 q) { return (b.x - a.x) * (q.y - a.y) - (b.y - a.y) * (q.x - a.x); }

// 0 where a centre exactly on the edge a -> b (interior on its left) counts, −1 where it does not:
// top (horizontal, right to left) and left (downward) edges count.
double tie_bias(dvec2 a, dvec2 b) { return (b.y < a.y || (b.y == a.y && b.x < a.x)) ? 0.0 : -1.0; }

vec2 window(vec4 c) { return (c.xy / c.w * 0.5 + 0.5) * vec2(imageSize(u_sum)); }

void cover(ivec2 p, vec3 x, bool front) {
#ifdef SUN_VIEW
    imageAtomicMin(u_near, p, ordered_bits(sun_depth(x)));
    imageAtomicAdd(u_sum, p, fixed_point(signed_sun_depth(x, front)));
#else
    imageAtomicAdd(u_sum, p, fixed_point(signed_eye_distance(x, vec2(p) + 0.5, front)));
#endif
}

// One triangle inside the near and far planes and the guard band (w > 0): its pixels, all of them
// or (LARGE_TRIANGLES) this invocation's share.
void rasterise(ClipVertex v0, ClipVertex v1, ClipVertex v2) {
    vec3 inv_w = 1.0 / vec3(v0.c.w, v1.c.w, v2.c.w);
    // Window coordinates: as they are for the interpolation (at the pixel centre), snapped for the
    // coverage.
    vec2 f0 = window(v0.c), f1 = window(v1.c), f2 = window(v2.c);
    dvec2 p0 = dvec2(floor(f0 * float(kSubpixel) + 0.5)), p1 = dvec2(floor(f1 * float(kSubpixel) + 0.5));
    dvec2 p2 = dvec2(floor(f2 * float(kSubpixel) + 0.5));
    double area = edge(p0, p1, p2);
    if (!(area != 0.0)) return;   // degenerate (or not a number)
    bool front = area > 0.0;
    vec3 x0 = v0.x, x1 = v1.x, x2 = v2.x;
    if (!front) {   // counter-clockwise from here on: the interior is left of every edge
        dvec2 p = p1;
        p1 = p2, p2 = p;
        vec2 f = f1;
        f1 = f2, f2 = f;
        vec3 x = x1;
        x1 = x2, x2 = x;
        inv_w = inv_w.xzy;
    }
    // The pixels whose centres the bounding box holds, within the target.
    dvec2 lo = min(min(p0, p1), p2), hi = max(max(p0, p1), p2);
    ivec2 first = max(ivec2(ceil((lo - 0.5 * kSubpixel) / kSubpixel)), ivec2(0));
    ivec2 last = min(ivec2(floor((hi - 0.5 * kSubpixel) / kSubpixel)), imageSize(u_sum) - 1);
    if (any(lessThan(last, first))) return;
    // e.x: edge p0 -> p1 (the weight of p2), e.y: p1 -> p2 (of p0), e.z: p2 -> p0 (of p1).
    dvec3 bias = dvec3(tie_bias(p0, p1), tie_bias(p1, p2), tie_bias(p2, p0));
#ifdef LARGE_TRIANGLES
    uint width = uint(last.x - first.x + 1), pixels = width * uint(last.y - first.y + 1);
    uint stride = gl_NumWorkGroups.y * gl_WorkGroupSize.x;
    for (uint k = gl_WorkGroupID.y * gl_WorkGroupSize.x + gl_LocalInvocationIndex; k < pixels; k += stride) {
        ivec2 px = first + ivec2(k % width, k / width);
        dvec2 q = (dvec2(px) + 0.5) * kSubpixel;
        dvec3 e = dvec3(edge(p0, p1, q), edge(p1, p2, q), edge(p2, p0, q));
#else
    dvec3 step = kSubpixel * dvec3(p1.y - p0.y, p2.y - p1.y, p0.y - p2.y);   // −dE/dx per pixel
    for (int j = first.y; j <= last.y; ++j) {
        dvec2 q = (dvec2(first.x, j) + 0.5) * kSubpixel;
        dvec3 e = dvec3(edge(p0, p1, q), edge(p1, p2, q), edge(p2, p0, q)) + step;
        for (int i = first.x; i <= last.x; ++i) {
            e -= step;
            ivec2 px = ivec2(i, j);
#endif
            if (any(lessThan(e + bias, dvec3(0.0)))) continue;
            vec2 c = vec2(px) + 0.5;
            vec3 l = vec3(edge_f(f1, f2, c), edge_f(f2, f0, c), edge_f(f0, f1, c)) * inv_w;   // perspective-correct: over w
            cover(px, (l.x * x0 + l.y * x1 + l.z * x2) / (l.x + l.y + l.z), front);
#ifndef LARGE_TRIANGLES
        }
#endif
    }
}

#ifndef LARGE_TRIANGLES
// Lists `triangle` for the second dispatch when its window bounding box [lo, hi] holds more than
// RANRYU_RASTER_LARGE_PIXELS pixels of the target and the list has room.
bool deferred(vec2 lo, vec2 hi, uint triangle) {
    vec2 span = clamp(hi, vec2(0.0), vec2(imageSize(u_sum))) - clamp(lo, vec2(0.0), vec2(imageSize(u_sum)));
    if (span.x * span.y <= float(RANRYU_RASTER_LARGE_PIXELS)) return false;
    uint k = atomicAdd(large[kView].w, 1u);
    if (k >= RANRYU_RASTER_LARGE_CAPACITY) return false;
    large_triangles[kView * RANRYU_RASTER_LARGE_CAPACITY + k] = triangle;
    atomicMax(large[kView].x, k + 1u);
    return true;
}
#endif

ClipVertex clip_vertex(uint i) {
    vec3 x = vertices[i].position.xyz;
#ifdef SUN_VIEW
    return ClipVertex(u_shadow_matrix * vec4(x, 1.0), x);
#else
    return ClipVertex(frame.view_proj * vec4(x, 1.0), x);
#endif
}

void main() {
#ifdef LARGE_TRIANGLES
    if (gl_WorkGroupID.x >= large[kView].x) return;
    uint triangle = large_triangles[kView * RANRYU_RASTER_LARGE_CAPACITY + gl_WorkGroupID.x];
#else
    uint triangle = flat_group() * gl_WorkGroupSize.x + gl_LocalInvocationIndex;
    if (triangle >= raster.w) return;
#endif
    ClipVertex v[3] = ClipVertex[](clip_vertex(3u * triangle), clip_vertex(3u * triangle + 1u), clip_vertex(3u * triangle + 2u));
    bool inside = true;
    for (int k = 0; k < 6; ++k) {
        vec3 d = vec3(dot(kPlanes[k], v[0].c), dot(kPlanes[k], v[1].c), dot(kPlanes[k], v[2].c));
        if (all(lessThan(d, vec3(0.0)))) return;   // wholly outside one plane
        inside = inside && all(greaterThanEqual(d, vec3(0.0)));
    }
    if (inside) {
#ifndef LARGE_TRIANGLES
        vec2 a = window(v[0].c), b = window(v[1].c), c = window(v[2].c);
        if (deferred(min(min(a, b), c), max(max(a, b), c), triangle)) return;
#endif
        rasterise(v[0], v[1], v[2]);
        return;
    }
    // Sutherland-Hodgman against the six planes (3 + 6 vertices at most), then a fan: its inner
    // edges are shared, so the top-left rule counts their pixels once.
    ClipVertex poly[9], next[9];
    poly[0] = v[0], poly[1] = v[1], poly[2] = v[2];
    int n = 3;
    for (int k = 0; k < 6 && n > 0; ++k) {
        int m = 0;
        for (int i = 0; i < n; ++i) {
            ClipVertex a = poly[i], b = poly[i + 1 == n ? 0 : i + 1];
            float da = dot(kPlanes[k], a.c), db = dot(kPlanes[k], b.c);
            if (da >= 0.0) next[m++] = a;
            if ((da >= 0.0) != (db >= 0.0)) {
                // From the inside vertex: the two triangles that share the edge, which walk it in
                // opposite directions, get the very same bits, and no crack opens between them.
                ClipVertex from = da >= 0.0 ? a : b, to = da >= 0.0 ? b : a;
                float t = max(da, db) / (max(da, db) - min(da, db));
                next[m++] = ClipVertex(mix(from.c, to.c, t), mix(from.x, to.x, t));
            }
        }
        for (int i = 0; i < m; ++i) poly[i] = next[i];
        n = m;
    }
#ifndef LARGE_TRIANGLES
    vec2 lo = vec2(1e30), hi = vec2(-1e30);
    for (int i = 0; i < n; ++i) {
        vec2 w = window(poly[i].c);
        lo = min(lo, w), hi = max(hi, w);
    }
    if (n >= 3 && deferred(lo, hi, triangle)) return;
#endif
    for (int i = 1; i + 1 < n; ++i) rasterise(poly[0], poly[i], poly[i + 1]);
}
