#version 430
// Cell ranges and reorder (METHOD.md §1 step 3), one invocation per sorted index i:
//   - from the keys sorted ascending, the run of each key:
//         cell_start[k] = first i with key[i] = k,   cell_end[k] = last such i + 1.
//     Cells with no particle keep what they held: the 0, 0 they were cleared to (NeighbourGrid::build
//     with clear), or a stale entry that readers reject (sph_common.glsl, fluid_run).
//     Example: keys 2 2 5 7 7 7 -> start[2]=0 end[2]=2, start[5]=2 end[5]=3, start[7]=3 end[7]=6.
//   - the gather of the particle arrays into sorted order,
//     out[i] = in[value[i]],
// so that the particles of one cell, and of neighbouring cells, are close in memory. With
// RANRYU_REORDER_NOISE_SEED the turbulence's carried noise seeds move with them.
#include "../../shared/bindings.h"

layout(local_size_x = 256) in;
layout(std140, binding = RANRYU_UBO_GRID) uniform GridBlock { GridParams grid; };
layout(std430, binding = RANRYU_SSBO_SORT_KEYS) readonly buffer Keys { uint keys[]; };
layout(std430, binding = RANRYU_SSBO_SORT_VALUES) readonly buffer Values { uint values[]; };
layout(std430, binding = RANRYU_SSBO_CELL_START) writeonly buffer Start { uint cell_start[]; };
layout(std430, binding = RANRYU_SSBO_CELL_END) writeonly buffer End { uint cell_end[]; };
layout(std430, binding = RANRYU_SSBO_POSITION) readonly buffer Positions { vec4 position[]; };
layout(std430, binding = RANRYU_SSBO_VELOCITY) readonly buffer Velocities { vec4 velocity[]; };
layout(std430, binding = RANRYU_SSBO_SORTED_POSITION) writeonly buffer SortedPositions { vec4 sorted_position[]; };
layout(std430, binding = RANRYU_SSBO_SORTED_VELOCITY) writeonly buffer SortedVelocities { vec4 sorted_velocity[]; };
#ifdef RANRYU_REORDER_NOISE_SEED
layout(std430, binding = RANRYU_SSBO_NOISE_SEED) readonly buffer Seeds { NoiseSeed seed[]; };
layout(std430, binding = RANRYU_SSBO_SORTED_NOISE_SEED) writeonly buffer SortedSeeds { NoiseSeed sorted_seed[]; };
#endif

void main() {
    uint i = gl_GlobalInvocationID.x;
    uint n = grid.count;
    if (i >= n) return;
    uint k = keys[i];
    if (i == 0u || keys[i - 1u] != k) cell_start[k] = i;
    if (i + 1u == n || keys[i + 1u] != k) cell_end[k] = i + 1u;
    uint src = values[i];
    sorted_position[i] = position[src];
    sorted_velocity[i] = velocity[src];
#ifdef RANRYU_REORDER_NOISE_SEED
    sorted_seed[i] = seed[src];
#endif
}
