#version 430
// Reorder (METHOD.md §1 step 3): gathers the particle arrays into sorted order,
//     out[i] = in[value[i]],
// so that the particles of one cell, and of neighbouring cells, are close in memory. With
// RANRYU_REORDER_NOISE_SEED the turbulence's carried noise seeds move with them.
#include "../../shared/bindings.h"

layout(local_size_x = 256) in;
layout(std140, binding = RANRYU_UBO_GRID) uniform GridBlock { GridParams grid; };
layout(std430, binding = RANRYU_SSBO_SORT_VALUES) readonly buffer Values { uint values[]; };
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
    if (i >= grid.count) return;
    uint src = values[i];
    sorted_position[i] = position[src];
    sorted_velocity[i] = velocity[src];
#ifdef RANRYU_REORDER_NOISE_SEED
    sorted_seed[i] = seed[src];
#endif
}
