#version 430
// Bitonic sort, the tail of a stage k > BITONIC_TILE (bitonic.glsl): the half-cleaner steps of
// strides j = BITONIC_TILE/2 .. 1, whose comparators stay inside one tile, in shared memory.
//   in/out  keys, values (blocks Keys, Values), first u_count pairs
//   u_stage.x = k (the stride comes from the loop)
// One workgroup per tile: dispatch ceil(u_count / BITONIC_TILE) groups.
#include "sim/sort/bitonic.glsl"

layout(local_size_x = BITONIC_GROUP) in;

#include "sim/sort/bitonic_tile.glsl"

layout(location = RANRYU_LOC_STAGE) uniform uvec2 u_stage;   // (k, j); j unused here

void main() {
    const uint first = gl_WorkGroupID.x * uint(BITONIC_TILE);
    load_tile(first);
    for (uint j = uint(BITONIC_TILE) >> 1u; j > 0u; j >>= 1u) step_tile(u_stage.x, j);
    store_tile(first);
}
