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

// The cells (center.x + x0 .. center.x + x1, center.y + dy, center.z + dz) as one run of sorted
// particles. With linear keys the cells of an x-row have consecutive keys, so their particles are
// contiguous and the whole row is one run [first start, last end); Morton keys give one cell a call.
uvec2 row_run(ivec3 center, int x0, int x1, int dy, int dz, bool fluid) {
    uint s = 0xFFFFFFFFu, e = 0u;
    for (int dx = x0; dx <= x1; ++dx) {
        ivec3 c = center + ivec3(dx, dy, dz);
        if (!cell_inside(c)) continue;
        uint key = cell_key(c);
        uvec2 r = fluid ? fluid_run(key) : boundary_run(key);
        if (r.y > r.x) { s = min(s, r.x); e = max(e, r.y); }
    }
    return s < e ? uvec2(s, e) : uvec2(0u);
}

// The rows of cells around a particle: dz_, dy_ in -1..1 and x0_ stepping through -1..1 one cell
// at a time (Morton keys) or as one row (linear keys). The body takes the row's run with
//     uvec2 run = row_run(center, x0_, ROW_END(x0_), dy_, dz_, fluid);
// and loops over [run.x, run.y).
#define FOR_EACH_ROW                                                                          \
    for (int dz_ = -1; dz_ <= 1; ++dz_)                                                       \
    for (int dy_ = -1; dy_ <= 1; ++dy_)                                                       \
    for (int x0_ = -1; x0_ <= 1; x0_ += (grid.morton != 0u ? 1 : 3))
#define ROW_END(x0) (grid.morton != 0u ? (x0) : 1)

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
