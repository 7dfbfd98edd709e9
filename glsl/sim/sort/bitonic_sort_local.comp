#version 430
// Bitonic sort, first pass (bitonic.glsl): sorts every tile of BITONIC_TILE consecutive pairs by
// (key, value) in shared memory, all stages k = 2 .. BITONIC_TILE.
//   in/out  keys, values (blocks Keys, Values), first u_count pairs; each tile
//           [t*BITONIC_TILE, (t+1)*BITONIC_TILE) ∩ [0, u_count) comes out ascending
// One workgroup per tile: dispatch ceil(u_count / BITONIC_TILE) groups. When u_count <=
// BITONIC_TILE this one dispatch is the whole sort.
#include "sim/sort/bitonic.glsl"

layout(local_size_x = BITONIC_GROUP) in;

#include "sim/sort/bitonic_tile.glsl"

void main() {
    const uint first = gl_WorkGroupID.x * uint(BITONIC_TILE);
    load_tile(first);
    for (uint k = 2u; k <= uint(BITONIC_TILE); k <<= 1u)
        for (uint j = k >> 1u; j > 0u; j >>= 1u) step_tile(k, j);
    store_tile(first);
}
