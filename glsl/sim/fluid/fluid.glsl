// The fluid state every SPH pass reads (engine/sim/fluid.h, docs/SPH.md): the parameter blocks, the
// step record, the neighbour grid's cell ranges and the boundary particles, and the runs of particles
// in the 27 cells around a particle. The including pass declares its per-particle arrays next.
#include "../../shared/bindings.h"

layout(std140, binding = RANRYU_UBO_GRID) uniform GridBlock { GridParams grid; };
layout(std140, binding = RANRYU_UBO_SPH) uniform SphBlock { SphParams sph; };
layout(std430) coherent buffer Step { StepState step; FrameExtreme extreme[]; };   // extreme[]: extremes.glsl
layout(std430) readonly buffer CellRange { uvec2 cell_range[]; }; // per key: first sorted index of the cell, one past its last
layout(std430) readonly buffer SortedKeys { uint sorted_keys[]; }; // per sorted index: the key (validates ranges)
layout(std430) readonly buffer Boundary { vec4 boundary[]; };      // xyz, w: psi_b, in cell order
layout(std430) readonly buffer BoundaryCellRange { uvec2 boundary_range[]; };

#include "../grid.glsl"
#include "../kernel.glsl"

// The fluid's kernel, of support h (eq. (1)), its constants read from SphParams (kernel.glsl).
float kernel_w(float r) { return kernel_w_of(r, sph.inv_h, sph.w_scale); }
vec3 kernel_grad(vec3 d, float r) { return kernel_grad_of(d, r, sph.inv_h, sph.grad_scale); }

// A parked particle (position.w = -1): one of the emitter's budget not poured in yet
// (engine/sim/fluid.h). It waits below the tank, farther than a support from everything else, and the
// integrations leave it there at rest, out of the guard's records.
bool parked(vec4 position) { return position.w < -0.5; }

// Keeps the maximum of non-negative floats with atomicMax on their bits (see StepState).
uint max_bits(float x) { return floatBitsToUint(max(x, 0.0)); }

// The fluid particles of cell `key`: the run [x, y) of the sorted arrays, or an empty run.
// The fluid's cell ranges are never cleared (a clear of every cell costs more than the substep's
// sort): an entry is current only if the sorted key at its start is `key`. A stale entry fails that
// test, because a cell that no particle has this substep has no particle with its key.
uvec2 fluid_run(uint key) {
    uvec2 r = cell_range[key];
    return r.x < sph.particle_count && sorted_keys[r.x] == key ? r : uvec2(0u);
}

// The boundary's ranges were cleared when they were built (once, at start): empty cells read 0, 0.
uvec2 boundary_run(uint key) { return boundary_range[key]; }

// The particles of the cell at `c`, as a run of the sorted arrays (empty outside the grid).
uvec2 cell_run(ivec3 c, bool fluid) {
    if (!cell_inside(c)) return uvec2(0u);
    uint key = cell_key(c);
    return fluid ? fluid_run(key) : boundary_run(key);
}

// The runs of particles around a particle: the body of FOR_EACH_RUN reads
//     uvec2 run = NEIGHBOUR_RUN(center, fluid);
// and loops over [run.x, run.y). With RANRYU_MERGE_ROWS (linear keys only; the Fluid defines it then)
// the three cells of an x-row have consecutive keys, so their particles are contiguous and the row is
// one run: 9 runs instead of 27. The merge is written without a loop: a loop form (min/max over the
// cells with `continue`) read wrong sums on NVIDIA's driver 580 though not on Mesa.
uvec2 merge_row(uvec2 a, uvec2 b, uvec2 c) {
    bool has_a = a.y > a.x, has_b = b.y > b.x, has_c = c.y > c.x;
    uint first = has_a ? a.x : (has_b ? b.x : c.x);
    uint last = has_c ? c.y : (has_b ? b.y : a.y);
    return (has_a || has_b || has_c) ? uvec2(first, last) : uvec2(0u);
}

#if defined(RANRYU_MERGE_ROWS)
const uint kNeighbourRuns = 9u;   // the runs FOR_EACH_RUN visits
#define FOR_EACH_RUN                          \
    for (int dz_ = -1; dz_ <= 1; ++dz_)       \
    for (int dy_ = -1; dy_ <= 1; ++dy_)
#define NEIGHBOUR_RUN(center, fluid)                                       \
    merge_row(cell_run((center) + ivec3(-1, dy_, dz_), fluid),             \
              cell_run((center) + ivec3(0, dy_, dz_), fluid),              \
              cell_run((center) + ivec3(1, dy_, dz_), fluid))
#else
const uint kNeighbourRuns = 27u;
#define FOR_EACH_RUN                          \
    for (int dz_ = -1; dz_ <= 1; ++dz_)       \
    for (int dy_ = -1; dy_ <= 1; ++dy_)       \
    for (int dx_ = -1; dx_ <= 1; ++dx_)
#define NEIGHBOUR_RUN(center, fluid) cell_run((center) + ivec3(dx_, dy_, dz_), fluid)
#endif

// The flags a density pass stores in density[i].w (as the bits of a uint) for the passes after it:
const uint kMasksComplete = 1u;    // the neighbour masks hold every fluid neighbour of i (neighbours.glsl)
const uint kBoundaryNear = 2u;     // some boundary particle lies within h of i
const uint kDeficient = 4u;        // fewer neighbours than a full support (DFSPH's divergence solve, docs/DFSPH.md (D5))
const uint kBoundaryMasksComplete = 8u;   // with RANRYU_BOUNDARY_MASKS: the boundary masks hold every boundary neighbour of i
// With RANRYU_BOUNDARY_SKIN (PBF) the boundary masks hold the boundary particles within h + skin,
// skin = kBoundarySkin h, of where the density pass found them (neighbours.glsl).
const float kBoundarySkin = 0.25;

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
