#version 430
// Cell ranges and reorder (docs/METHOD.md §1 step 3), one invocation per sorted index i:
//   - from the keys sorted ascending, the run of each key:
//         cell_range[k] = (first i with key[i] = k, last such i + 1).
//     Cells with no particle keep what they held: the 0, 0 they were cleared to (NeighbourGrid::build
//     with clear), or a stale entry that readers reject (sim/fluid/fluid.glsl, fluid_run).
//     Example: keys 2 2 5 7 7 7 -> range[2] = (0, 2), range[5] = (2, 3), range[7] = (3, 6).
//   - the gather of the particle arrays into sorted order,
//     out[i] = in[value[i]],
// so that the particles of one cell, and of neighbouring cells, are close in memory. With
// RANRYU_CARRIED_ARRAYS = 1, 2 or 3, that many more per-particle arrays move with them (the fluid's
// carried arrays: the turbulence's noise seeds, a solver's step start and warm start), each of carried_words[a]
// 32-bit words a particle.
#include "../../shared/bindings.h"

layout(local_size_x = 256) in;
layout(std140, binding = RANRYU_UBO_GRID) uniform GridBlock { GridParams grid; };
layout(std430) readonly buffer SortedKeys { uint keys[]; };
layout(std430) readonly buffer SortedValues { uint values[]; };
layout(std430) writeonly buffer CellRange { uvec2 cell_range[]; };
layout(std430) readonly buffer Positions { vec4 position[]; };
layout(std430) readonly buffer Velocities { vec4 velocity[]; };
layout(std430) writeonly buffer SortedPositions { vec4 sorted_position[]; };
layout(std430) writeonly buffer SortedVelocities { vec4 sorted_velocity[]; };
#if RANRYU_CARRIED_ARRAYS >= 1
layout(location = RANRYU_LOC_AUX) uniform uvec3 carried_words;
layout(std430) readonly buffer Carried0 { uint carried0[]; };
layout(std430) writeonly buffer SortedCarried0 { uint sorted_carried0[]; };
#endif
#if RANRYU_CARRIED_ARRAYS >= 2
layout(std430) readonly buffer Carried1 { uint carried1[]; };
layout(std430) writeonly buffer SortedCarried1 { uint sorted_carried1[]; };
#endif
#if RANRYU_CARRIED_ARRAYS >= 3
layout(std430) readonly buffer Carried2 { uint carried2[]; };
layout(std430) writeonly buffer SortedCarried2 { uint sorted_carried2[]; };
#endif

void main() {
    uint i = gl_GlobalInvocationID.x;
    uint n = grid.count;
    if (i >= n) return;
    uint k = keys[i];
    if (i == 0u || keys[i - 1u] != k) cell_range[k].x = i;
    if (i + 1u == n || keys[i + 1u] != k) cell_range[k].y = i + 1u;
    uint src = values[i];
    sorted_position[i] = position[src];
    sorted_velocity[i] = velocity[src];
#if RANRYU_CARRIED_ARRAYS >= 1
    for (uint w = 0u; w < carried_words.x; ++w) sorted_carried0[i * carried_words.x + w] = carried0[src * carried_words.x + w];
#endif
#if RANRYU_CARRIED_ARRAYS >= 2
    for (uint w = 0u; w < carried_words.y; ++w) sorted_carried1[i * carried_words.y + w] = carried1[src * carried_words.y + w];
#endif
#if RANRYU_CARRIED_ARRAYS >= 3
    for (uint w = 0u; w < carried_words.z; ++w) sorted_carried2[i * carried_words.z + w] = carried2[src * carried_words.z + w];
#endif
}
