// Blocks every SPH pass binds (docs/SPH.md), and the runs of particles in the 27 cells around a
// particle, for fluid and for boundary particles. The including pass declares what it needs next.
#include "../../shared/bindings.h"

layout(std140, binding = RANRYU_UBO_GRID) uniform GridBlock { GridParams grid; };
layout(std140, binding = RANRYU_UBO_SPH) uniform SphBlock { SphParams sph; };
layout(std430, binding = RANRYU_SSBO_STEP) coherent buffer Step { StepState step; };
layout(std430, binding = RANRYU_SSBO_CELL_START) readonly buffer Start { uint cell_start[]; };
layout(std430, binding = RANRYU_SSBO_CELL_END) readonly buffer End { uint cell_end[]; };
layout(std430, binding = RANRYU_SSBO_SORT_KEYS) readonly buffer SortedKeys { uint sorted_keys[]; };
layout(std430, binding = RANRYU_SSBO_BOUNDARY) readonly buffer Boundary { vec4 boundary[]; };   // xyz, w: psi_b
layout(std430, binding = RANRYU_SSBO_BOUNDARY_CELL_START) readonly buffer BStart { uint boundary_start[]; };
layout(std430, binding = RANRYU_SSBO_BOUNDARY_CELL_END) readonly buffer BEnd { uint boundary_end[]; };

#include "../grid.glsl"
#include "../kernel.glsl"

// Keeps the maximum of non-negative floats with atomicMax on their bits (see StepState).
uint max_bits(float x) { return floatBitsToUint(max(x, 0.0)); }

// The fluid particles of cell `key`: the run [x, y) of the sorted arrays, or an empty run.
// The fluid's cell ranges are never cleared (a clear of every cell costs more than the substep's
// sort): an entry is current only if the sorted key at its start is `key`. A stale entry fails that
// test, because a cell that no particle has this substep has no particle with its key.
uvec2 fluid_run(uint key) {
    uint s = cell_start[key];
    if (s < sph.particle_count && sorted_keys[s] == key) return uvec2(s, cell_end[key]);
    return uvec2(0u);
}

// The boundary's ranges were cleared when they were built (once, at start): empty cells read 0, 0.
uvec2 boundary_run(uint key) { return uvec2(boundary_start[key], boundary_end[key]); }

// The particles of the cell at `c`, as a run of the sorted arrays (empty outside the grid).
uvec2 cell_run(ivec3 c, bool fluid) {
    if (!cell_inside(c)) return uvec2(0u);
    uint key = cell_key(c);
    return fluid ? fluid_run(key) : boundary_run(key);
}

// The 27 cells around a particle; the body reads NEIGHBOUR_CELL(center) and loops over the run
//     uvec2 run = cell_run(NEIGHBOUR_CELL(center), fluid);
// (Merging the three cells of an x-row into one run, which linear keys allow, gave wrong sums on
// NVIDIA's driver 580 though not on Mesa; docs/PERFORMANCE.md has the measurement.)
#define FOR_EACH_CELL                         \
    for (int dz_ = -1; dz_ <= 1; ++dz_)       \
    for (int dy_ = -1; dy_ <= 1; ++dy_)       \
    for (int dx_ = -1; dx_ <= 1; ++dx_)
#define NEIGHBOUR_CELL(center) ((center) + ivec3(dx_, dy_, dz_))

// Workgroup maxima of non-negative floats (as bits, see StepState), each with one invocation that
// has it, so that a pass makes one global atomic per workgroup instead of one per particle (a
// million atomics on one address serialise: measured 0.8 ms at 1M particles on an H100).
shared uint wg_max_;
shared uint wg_arg_;

// Every invocation of the workgroup must call this (it has barriers). Returns the workgroup's
// maximum in .x and an index that has it in .y.
uvec2 workgroup_max(uint bits, uint index) {
    if (gl_LocalInvocationIndex == 0u) wg_max_ = 0u;
    barrier();
    atomicMax(wg_max_, bits);
    barrier();
    if (bits == wg_max_ && bits != 0u) wg_arg_ = index;
    barrier();
    uvec2 r = uvec2(wg_max_, wg_arg_);
    barrier();
    return r;
}
