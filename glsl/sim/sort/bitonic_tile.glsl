// The shared-memory tile of the local bitonic passes: BITONIC_TILE consecutive pairs per workgroup,
// virtual pairs (0xFFFFFFFF, 0xFFFFFFFF) past u_count. Tie of a virtual pair with a real pair of the
// same bits: either order leaves the same bits in place, and only positions < u_count are stored.
#ifndef RANRYU_SORT_BITONIC_TILE_GLSL
#define RANRYU_SORT_BITONIC_TILE_GLSL

shared uint s_key[BITONIC_TILE];
shared uint s_value[BITONIC_TILE];

void load_tile(uint first) {
    for (uint q = 0u; q < uint(BITONIC_ITEMS); ++q) {
        const uint i = q * gl_WorkGroupSize.x + gl_LocalInvocationIndex;
        s_key[i] = 0xFFFFFFFFu;
        s_value[i] = 0xFFFFFFFFu;
        if (first + i < u_count) {
            s_key[i] = keys[first + i];
            s_value[i] = values[first + i];
        }
    }
    memoryBarrierShared();
    barrier();
}

void store_tile(uint first) {
    for (uint q = 0u; q < uint(BITONIC_ITEMS); ++q) {
        const uint i = q * gl_WorkGroupSize.x + gl_LocalInvocationIndex;
        if (first + i < u_count) {
            keys[first + i] = s_key[i];
            values[first + i] = s_value[i];
        }
    }
}

// One step (stage k, stride j < BITONIC_TILE) over the tile: BITONIC_TILE / 2 comparators.
void step_tile(uint k, uint j) {
    for (uint q = 0u; q < uint(BITONIC_ITEMS) / 2u; ++q) {
        const uint c = q * gl_WorkGroupSize.x + gl_LocalInvocationIndex;
        const uint lo = comparator_low(c, j);
        const uint hi = comparator_high(lo, k, j);
        const uint key_lo = s_key[lo], value_lo = s_value[lo];
        const uint key_hi = s_key[hi], value_hi = s_value[hi];
        if (pair_less(key_hi, value_hi, key_lo, value_lo)) {
            s_key[lo] = key_hi;
            s_value[lo] = value_hi;
            s_key[hi] = key_lo;
            s_value[hi] = value_lo;
        }
    }
    memoryBarrierShared();
    barrier();
}

#endif
