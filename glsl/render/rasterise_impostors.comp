#version 430
// "draw-particles" off the raster hardware (docs/RENDERING.md (R15)): the sphere impostors of
// impostor.vert and impostor.frag, rasterised by compute into two R32F targets of the frame's size
// bound as r32ui images. For particle i and each pixel p whose centre's eye ray meets its sphere,
// at window depth z_i(p) ≥ 0 (whose float bits order as the floats do):
//     without RESOLVE:  u_depth(p) = min(u_depth(p), bits(z_i(p)))
//     with RESOLVE:     u_id(p) = i + 1 where bits(z_i(p)) = u_depth(p)   (after the first; a tie
//                       of equal depths keeps either)
// The pixels tested are those whose centres the bounding box of the silhouette quad's projected
// corners (silhouette_corner) holds, within the target: the draw's quad covers the same silhouette,
// so both find the same pixels up to the rounding of the ray. z_i(p) is `precise`: both variants, each
// its own program, compute the very same bits.
// Not drawn, as in the draw: a parked particle (position.w = −1) and a sphere holding the eye; and,
// unlike the draw, which shows the part of it beyond the near plane, a sphere the near plane cuts.
// Dispatches: one invocation per particle (u_count); built with LARGE, the listed particles
// (ImpostorLarge), RANRYU_IMPOSTOR_LARGE_TILES workgroups each, whose invocations share its pixels.
#include "impostor.glsl"

layout(local_size_x = 64) in;
layout(std430) readonly buffer Positions { vec4 position[]; };
// x: listed (the LARGE dispatch's workgroups along x), y: RANRYU_IMPOSTOR_LARGE_TILES, z: 1,
// w: claimed (more than the capacity when some were left to their own invocation); then the indices.
layout(std430) buffer ImpostorLarge {
    uvec4 large;
    uint large_particles[];
};
#ifdef RESOLVE
layout(binding = RANRYU_IMG_IMPOSTOR_DEPTH, r32ui) readonly uniform uimage2D u_depth;
layout(binding = RANRYU_IMG_IMPOSTOR_ID, r32ui) writeonly uniform uimage2D u_id;
#else
layout(binding = RANRYU_IMG_IMPOSTOR_DEPTH, r32ui) uniform uimage2D u_depth;
#endif
layout(location = RANRYU_LOC_COUNT) uniform uint u_count;

#ifndef RANRYU_IMPOSTOR_CAPACITY
#define RANRYU_IMPOSTOR_CAPACITY RANRYU_IMPOSTOR_LARGE_CAPACITY
#endif

// Particle i's sphere centre c (view space) and the pixels [first, last] its silhouette's bounding
// box holds within the target; false where it is not drawn or covers no pixel centre.
bool place(uint i, out vec3 c, out ivec2 first, out ivec2 last) {
    vec4 x = position[i];
    c = (frame.view * vec4(x.xyz, 1.0)).xyz;
    float r = frame.material.w;
    first = ivec2(0), last = ivec2(-1);
    if (x.w < -0.5 || -c.z - r < near_plane()) return false;   // parked, or cut by the near plane
    vec2 size = frame.viewport.xy, lo = size + 1.0, hi = vec2(-1.0);
    for (int k = 0; k < 4; ++k) {
        vec4 q = frame.proj * vec4(silhouette_corner(c, r, vec2(float(k & 1), float(k >> 1)) * 2.0 - 1.0), 1.0);
        vec2 w = clamp((q.xy / q.w * 0.5 + 0.5) * size, vec2(-1.0), size + 1.0);
        lo = min(lo, w), hi = max(hi, w);
    }
    first = max(ivec2(ceil(lo - 0.5)), ivec2(0));
    last = min(ivec2(floor(hi - 0.5)), ivec2(size) - 1);
    return all(greaterThanEqual(last, first));
}

void cover(uint i, vec3 c, ivec2 p) {
    vec3 dir = view_ray(vec2(p) + 0.5);
    precise float t = sphere_front(dir, c, frame.material.w);
    if (t < 0.0) return;
    precise float z = window_depth(t * dir);
    uint bits = floatBitsToUint(z);
#ifdef RESOLVE
    if (imageLoad(u_depth, p).x == bits) imageStore(u_id, p, uvec4(i + 1u));
#else
    imageAtomicMin(u_depth, p, bits);
#endif
}

void main() {
#ifdef LARGE
    if (gl_WorkGroupID.x >= large.x) return;
    uint i = large_particles[gl_WorkGroupID.x];
#else
    uint i = gl_GlobalInvocationID.x;
    if (i >= u_count) return;
#endif
    vec3 c;
    ivec2 first, last;
    if (!place(i, c, first, last)) return;
    uint width = uint(last.x - first.x + 1), pixels = width * uint(last.y - first.y + 1);
#ifdef LARGE
    uint stride = gl_NumWorkGroups.y * gl_WorkGroupSize.x;
    for (uint k = gl_WorkGroupID.y * gl_WorkGroupSize.x + gl_LocalInvocationIndex; k < pixels; k += stride)
        cover(i, c, first + ivec2(k % width, k / width));
#else
    if (pixels > uint(RANRYU_IMPOSTOR_LARGE_PIXELS)) {
#ifdef RESOLVE
        // Every large one was listed: the LARGE dispatch resolves it. Otherwise this invocation
        // resolves it too (a listed one twice, the same id at the same pixels).
        if (large.w <= RANRYU_IMPOSTOR_CAPACITY) return;
#else
        uint k = atomicAdd(large.w, 1u);
        if (k < RANRYU_IMPOSTOR_CAPACITY) {
            large_particles[k] = i;
            atomicMax(large.x, k + 1u);
            return;
        }
#endif
    }
    for (int y = first.y; y <= last.y; ++y)
        for (int x = first.x; x <= last.x; ++x) cover(i, c, ivec2(x, y));
#endif
}
