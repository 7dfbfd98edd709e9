// Blocks every SPH pass binds (docs/SPH.md), and the neighbour loops over the 27 cells around a
// particle, for fluid and for boundary particles. The including pass declares what it needs next.
#include "../../shared/bindings.h"

layout(std140, binding = RANRYU_UBO_GRID) uniform GridBlock { GridParams grid; };
layout(std140, binding = RANRYU_UBO_SPH) uniform SphBlock { SphParams sph; };
layout(std430, binding = RANRYU_SSBO_STEP) coherent buffer Step { StepState step; };
layout(std430, binding = RANRYU_SSBO_CELL_START) readonly buffer Start { uint cell_start[]; };
layout(std430, binding = RANRYU_SSBO_CELL_END) readonly buffer End { uint cell_end[]; };
layout(std430, binding = RANRYU_SSBO_BOUNDARY) readonly buffer Boundary { vec4 boundary[]; };   // xyz, w: psi_b
layout(std430, binding = RANRYU_SSBO_BOUNDARY_CELL_START) readonly buffer BStart { uint boundary_start[]; };
layout(std430, binding = RANRYU_SSBO_BOUNDARY_CELL_END) readonly buffer BEnd { uint boundary_end[]; };

#include "../grid.glsl"
#include "../kernel.glsl"

// Keeps the maximum of non-negative floats with atomicMax on their bits (see StepState).
uint max_bits(float x) { return floatBitsToUint(max(x, 0.0)); }

// for every cell around `center`: body sees `key`
#define FOR_EACH_NEIGHBOUR_CELL(center, key)                      \
    for (int dz = -1; dz <= 1; ++dz)                              \
    for (int dy = -1; dy <= 1; ++dy)                              \
    for (int dx = -1; dx <= 1; ++dx)                              \
    if (cell_inside(center + ivec3(dx, dy, dz)))                  \
    for (uint key = cell_key(center + ivec3(dx, dy, dz)), once_ = 0u; once_ < 1u; ++once_)
