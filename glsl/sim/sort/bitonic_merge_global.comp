#version 430
// Bitonic sort, one step of stage k with stride j >= BITONIC_TILE (bitonic.glsl), over global
// memory: the flip (j = k/2) or a half-cleaner (j < k/2).
//   in/out  keys, values (blocks Keys, Values), first u_count pairs
//   u_stage = (k, j)
// Comparators c whose lower index is >= u_count are no-ops, and the lower index is >= c, so
// c < u_count covers every comparator that can act. Any number of groups works (grid-stride loop);
// dispatch enough for min(n/2, u_count) comparators, capped at the driver's group-count limit.
#include "sim/sort/bitonic.glsl"

layout(local_size_x = BITONIC_GROUP) in;

layout(location = RANRYU_LOC_STAGE) uniform uvec2 u_stage;   // (k, j)

void main() {
    const uint k = u_stage.x, j = u_stage.y;
    const uint stride = gl_NumWorkGroups.x * gl_WorkGroupSize.x;
    for (uint c = gl_GlobalInvocationID.x; c < u_count; c += stride) {
        const uint lo = comparator_low(c, j);
        const uint hi = comparator_high(lo, k, j);
        if (hi >= u_count) continue;
        const uint key_lo = keys[lo], value_lo = values[lo];
        const uint key_hi = keys[hi], value_hi = values[hi];
        if (pair_less(key_hi, value_hi, key_lo, value_lo)) {
            keys[lo] = key_hi;
            values[lo] = value_hi;
            keys[hi] = key_lo;
            values[hi] = value_lo;
        }
    }
}
