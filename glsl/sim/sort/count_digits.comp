#version 430
// Radix pass 1 of 3 (Satish et al. IPDPS 2009, "local histogram"): every workgroup counts the
// digits of one tile of RADIX_TILE keys.
//   in   keys (block Keys), the first u_count
//   out  histogram[RADIX_DIGITS + d*T + t] = number of keys of tile t whose digit is d, for every
//        d (zeros included), T = tile_count(); layout in radix.glsl
// One workgroup per tile: dispatch tile_count() groups.
#if defined(RANRYU_SUBGROUPS)
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_vote : require
#extension GL_KHR_shader_subgroup_ballot : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#endif
#include "sim/sort/radix.glsl"

layout(local_size_x = RADIX_GROUP) in;

#include "sim/sort/subgroup.glsl"

layout(std430) readonly buffer Keys { uint keys[]; };
layout(std430) writeonly buffer Histogram { uint histogram[]; };

shared uint s_count[RADIX_DIGITS];

void main() {
    const uint tile = gl_WorkGroupID.x;
    const uint tiles = tile_count();
    const uint first = tile * uint(RADIX_TILE);
    for (uint d = gl_LocalInvocationIndex; d < uint(RADIX_DIGITS); d += gl_WorkGroupSize.x) s_count[d] = 0u;
    sync_shared();
    // Strided reads: consecutive invocations read consecutive keys.
    for (uint k = 0u; k < uint(RADIX_ITEMS); ++k) {
        const uint i = first + k * gl_WorkGroupSize.x + gl_LocalInvocationIndex;
        const bool valid = i < u_count;
        const uint d = digit_of(keys[min(i, u_count - 1u)]);   // a clamped read: no branch before the vote
#ifdef SORT_SUBGROUP_ALGORITHM
        // Sorted input, equal keys and runs of one grid cell send a whole subgroup to one counter:
        // one atomic instead of a subgroup's worth serialised on the same address.
        if (sg_all_equal(valid ? d : 0xFFFFFFFFu)) {
            if (valid && sg_lane() == 0u) atomicAdd(s_count[d], sg_size());
        } else if (valid) {
            atomicAdd(s_count[d], 1u);
        }
#else
        if (valid) atomicAdd(s_count[d], 1u);
#endif
    }
    sync_shared();
    for (uint d = gl_LocalInvocationIndex; d < uint(RADIX_DIGITS); d += gl_WorkGroupSize.x)
        histogram[count_index(d, tile, tiles)] = s_count[d];
}
