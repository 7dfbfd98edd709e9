#version 430
// "draw-particles" off the raster hardware (docs/RENDERING.md (R15)): the sphere impostors of
// impostor.vert and impostor.frag, rasterised by compute into two R32F targets of the frame's size
// bound as r32ui images. For sphere s and each pixel p whose centre's eye ray meets it, at window
// depth z_s(p) ≥ 0 (whose float bits order as the floats do):
//     without RESOLVE:  u_depth(p) = min(u_depth(p), bits(z_s(p)))
//     with RESOLVE:     u_id(p) = id(s) + 1 where bits(z_s(p)) = u_depth(p)   (after the first; a tie
//                       of equal depths keeps either)
// The pixels tested are those whose centres the bounding box of the silhouette quad's projected
// corners (silhouette_corner) holds, within the target: the draw's quad covers the same silhouette,
// so both find the same pixels up to the rounding of the ray. The two walks are one file built twice
// (RESOLVE), not two passes' files, because the second must retrace the first exactly: the sphere's
// view-space centre, its box (whose size decides whether it is listed for LARGE) and z_s(p) are
// `precise`, so every variant, each its own program, computes the very same bits.
// A sphere's id is its particle's index; built with BY_LEVEL (sub-particles, render/renderer.h), a
// sub-particle's is kChild | its index, and a sphere of level E has radius r/2^E: parents (u_children.x
// = 0) carry their levels word, one that the spawn pass split is not drawn (its sub-particles are);
// sub-particles (u_children.x = 1) carry E in position.w, and are as many as their draw's instances.
// Not drawn, as in the draw: a parked particle (position.w = −1) and a sphere holding the eye. A sphere
// the near plane cuts is drawn as the draw draws it: the hardware clips its quad at the near plane, so
// a pixel shows the sphere where its ray meets it and meets the quad's plane beyond the near plane (the
// box: the quad clipped there, projected; the front's depth clamped to ≥ 0 as below).
// Dispatches: one invocation per particle (u_count); built with BY_LEVEL, for the sub-particles, their
// spawn pass's indirect dispatch (u_children.y sub-particles a workgroup, surface/dispatch_2d.glsl);
// built with LARGE, the listed spheres (ImpostorLarge), RANRYU_IMPOSTOR_LARGE_TILES workgroups each,
// whose invocations share its pixels.
#include "impostor.glsl"
#include "../surface/dispatch_2d.glsl"

layout(local_size_x = 64) in;
layout(std430) readonly buffer Positions { vec4 position[]; };
// x: listed (the LARGE dispatch's workgroups along x), y: RANRYU_IMPOSTOR_LARGE_TILES, z: 1,
// w: claimed (more than the capacity when some were left to their own invocation); then the ids.
layout(std430) buffer ImpostorLarge {
    uvec4 large;
    uint large_spheres[];
};
#ifdef RESOLVE
layout(binding = RANRYU_IMG_IMPOSTOR_DEPTH, r32ui) readonly uniform uimage2D u_depth;
layout(binding = RANRYU_IMG_IMPOSTOR_ID, r32ui) writeonly uniform uimage2D u_id;
#else
layout(binding = RANRYU_IMG_IMPOSTOR_DEPTH, r32ui) uniform uimage2D u_depth;
#endif
layout(location = RANRYU_LOC_COUNT) uniform uint u_count;
#ifdef BY_LEVEL
layout(std430) readonly buffer SubparticleLevels { uint parent_level[]; };
layout(std430) readonly buffer SubparticlePositions { vec4 sub_position[]; };
layout(std430) readonly buffer Subparticles { uint sub_words[]; };   // their draw's arguments at word u_children.z
// x: 0 parents, 1 sub-particles; y: sub-particles a workgroup; z: the word of their draw's arguments
// (4 vertices, instances: the sub-particles) in Subparticles
layout(location = RANRYU_LOC_IMPOSTOR_CHILDREN) uniform uvec3 u_children;
#endif

#ifndef RANRYU_IMPOSTOR_CAPACITY
#define RANRYU_IMPOSTOR_CAPACITY RANRYU_IMPOSTOR_LARGE_CAPACITY
#endif
const uint kChild = 0x80000000u;

// The window position of view-space point p (q.w > 0), within the target grown by a pixel.
vec2 window_of(vec3 p) {
    vec2 size = frame.viewport.xy;
    precise vec4 q = frame.proj * vec4(p, 1.0);
    precise vec2 w = clamp((q.xy / q.w * 0.5 + 0.5) * size, vec2(-1.0), size + 1.0);
    return w;
}

// Sphere `id`'s centre c (view space) and radius r, whether the near plane clips its quad, and the
// pixels [first, last] its silhouette's bounding box holds within the target (the quad clipped at the
// near plane); false where it is not drawn or covers no pixel centre.
bool place(uint id, out vec3 c, out float r, out bool cut, out ivec2 first, out ivec2 last) {
    first = ivec2(0), last = ivec2(-1);
    cut = false;
    r = frame.material.w;
#ifdef BY_LEVEL
    bool child = (id & kChild) != 0u;
    vec4 x = child ? sub_position[id & ~kChild] : position[id];
    if (child) r = ldexp(r, -int(min(uint(x.w), 3u)));
    else if ((parent_level[id] >> RANRYU_SUBPARTICLE_SPLIT_SHIFT) != 0u) return false;   // split: its sub-particles are drawn
    bool parked = !child && x.w < -0.5;
#else
    vec4 x = position[id];
    bool parked = x.w < -0.5;
#endif
    precise vec3 centre = (frame.view * vec4(x.xyz, 1.0)).xyz;
    c = centre;
    if (parked || length(centre) <= r * 1.001) return false;   // parked, or the eye inside the sphere (impostor.vert)
    // The quad's corners in turn around it. Where one lies in front of the near plane the draw's quad is
    // clipped there (`cut`), and the box is the clipped quad's (Sutherland and Hodgman: each corner
    // beyond the plane, and each edge's crossing of it); where none does, the quad is whole.
    float near = near_plane();
    const vec2 kRing[4] = vec2[4](vec2(-1.0, -1.0), vec2(1.0, -1.0), vec2(1.0, 1.0), vec2(-1.0, 1.0));
    precise vec3 q[4];
    for (int k = 0; k < 4; ++k) {
        q[k] = silhouette_corner(centre, r, kRing[k]);
        cut = cut || -q[k].z < near;
    }
    vec2 size = frame.viewport.xy;
    precise vec2 lo = size + 1.0, hi = vec2(-1.0);
    for (int k = 0; k < 4; ++k) {
        precise vec3 a = q[k], b = q[(k + 1) & 3];
        bool a_in = -a.z >= near;
        if (a_in) {
            precise vec2 w = window_of(a);
            lo = min(lo, w), hi = max(hi, w);
        }
        if (a_in != (-b.z >= near)) {
            precise vec3 m = mix(a, b, (-near - a.z) / (b.z - a.z));
            m.z = -near;
            precise vec2 w = window_of(m);
            lo = min(lo, w), hi = max(hi, w);
        }
    }
    first = max(ivec2(ceil(lo - 0.5)), ivec2(0));
    last = min(ivec2(floor(hi - 0.5)), ivec2(size) - 1);
    return all(greaterThanEqual(last, first));
}

// Where the quad is clipped (`cut`), a pixel is covered only where its ray meets the quad's plane
// (through c, facing the eye: t_q = |c|²/(dir·c)) beyond the near plane, as the draw's clipped quad.
void cover(uint id, vec3 c, float r, bool cut, ivec2 p) {
    vec3 dir = view_ray(vec2(p) + 0.5);
    precise float t = sphere_front(dir, c, r);
    if (t < 0.0) return;
    if (cut) {
        precise float quad_depth = -dir.z * dot(c, c) / dot(dir, c);   // both builds decide alike
        if (quad_depth < near_plane()) return;
    }
    precise float z = max(window_depth(t * dir), 0.0);   // ≥ 0 (near the near plane, rounding may give −0 or −ε)
    uint bits = floatBitsToUint(z);
#ifdef RESOLVE
    if (imageLoad(u_depth, p).x == bits) imageStore(u_id, p, uvec4(id + 1u));
#else
    imageAtomicMin(u_depth, p, bits);
#endif
}

#ifdef LARGE
void main() {
    if (gl_WorkGroupID.x >= large.x) return;
    uint id = large_spheres[gl_WorkGroupID.x];
    vec3 c;
    float r;
    bool cut;
    ivec2 first, last;
    if (!place(id, c, r, cut, first, last)) return;
    uint width = uint(last.x - first.x + 1), pixels = width * uint(last.y - first.y + 1);
    uint stride = gl_NumWorkGroups.y * gl_WorkGroupSize.x;
    for (uint k = gl_WorkGroupID.y * gl_WorkGroupSize.x + gl_LocalInvocationIndex; k < pixels; k += stride)
        cover(id, c, r, cut, first + ivec2(k % width, k / width));
}
#else
// Sphere `id` whole, or listed for the LARGE dispatch when its box holds more than
// RANRYU_IMPOSTOR_LARGE_PIXELS pixels and the list has room.
void rasterise(uint id) {
    vec3 c;
    float r;
    bool cut;
    ivec2 first, last;
    if (!place(id, c, r, cut, first, last)) return;
    uint pixels = uint(last.x - first.x + 1) * uint(last.y - first.y + 1);
    if (pixels > uint(RANRYU_IMPOSTOR_LARGE_PIXELS)) {
#ifdef RESOLVE
        // Every large one was listed: the LARGE dispatch resolves it. Otherwise this invocation
        // resolves it too (a listed one twice, the same id at the same pixels).
        if (large.w <= RANRYU_IMPOSTOR_CAPACITY) return;
#else
        uint k = atomicAdd(large.w, 1u);
        if (k < RANRYU_IMPOSTOR_CAPACITY) {
            large_spheres[k] = id;
            atomicMax(large.x, k + 1u);
            return;
        }
#endif
    }
    for (int y = first.y; y <= last.y; ++y)
        for (int x = first.x; x <= last.x; ++x) cover(id, c, r, cut, ivec2(x, y));
}

void main() {
#ifdef BY_LEVEL
    if (u_children.x != 0u) {   // this workgroup's share of the spawn pass's sub-particles
        uint subparticles = sub_words[u_children.z + 1u];
        for (uint k = gl_LocalInvocationIndex; k < u_children.y; k += gl_WorkGroupSize.x) {
            uint s = flat_group() * u_children.y + k;
            if (s < subparticles) rasterise(kChild | s);
        }
        return;
    }
#endif
    if (gl_GlobalInvocationID.x < u_count) rasterise(gl_GlobalInvocationID.x);
}
#endif
