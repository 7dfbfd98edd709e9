#version 430
// "level-set" (docs/METHOD.md §7): φ at every node of the grid that place_grid laid out,
//     φ(x) = V · Σ_i W(|x - x_i|, R) - iso,
// W the cubic spline of glsl/sim/kernel.glsl with support R, V = dx^3 (so V·ΣW ≈ 1 inside liquid at
// rest; engine/surface/level_set.h gives the choice of R and iso).
// A GATHER: each node loops over the neighbour-grid cells that the box [x - R - m, x + R + m] touches
// (m = search_margin) and over their particles' runs of the cell-ordered positions. No atomics; each
// node's sum runs in a fixed order, so φ is the same from run to run.
//   - Particles are found in the cell they were sorted into. The margin m covers particles that have
//     moved since (the SPH integrates after the sort): one within R of x now was within R + m of x
//     then. W vanishes beyond R, so searching farther never changes the sum, only its cost.
//   - The cell range is clamped to the grid like grid_cell() clamps particles, so particles outside
//     the neighbour grid (kept in its border cells) are found too: clamping is monotone.
//   - Cell ranges need not have been cleared (NeighbourGrid::build with clear = false): a run is taken
//     only if the sorted key at its start is the cell's own, as fluid_run() in sim/fluid/fluid.glsl.
// Dispatch: glDispatchComputeIndirect with surface_grid.dispatch; one invocation per node.
// Built with RANRYU_SUBPARTICLES (level_set.h), split parents are skipped and the children's splat added.
// Built with RANRYU_SPLATTED (anisotropic kernels, docs/SURFACE.md (S7)), there is no gather: the
// particles' kernels were splatted (splat_particles.comp, with the sub-particles' if any), and φ is
// that fixed-point sum less iso; the sum is reset to 0 for the next frame.
#include "../shared/bindings.h"

layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;
layout(std140, binding = RANRYU_UBO_GRID) uniform GridBlock { GridParams grid; };
layout(std140, binding = RANRYU_UBO_SURFACE) uniform SurfaceBlock { SurfaceParams surface; };
layout(std430) readonly buffer Positions { vec4 sorted_position[]; };
layout(std430) readonly buffer CellRange { uvec2 cell_range[]; };
layout(std430) readonly buffer SortedKeys { uint sorted_keys[]; };
layout(std430) readonly buffer SurfaceGridState { SurfaceGrid surface_grid; };
layout(std430) writeonly buffer Phi { float phi[]; };
#if defined(RANRYU_SUBPARTICLES) || defined(RANRYU_SPLATTED)
layout(std430) buffer SplatGrid { uint splat[]; };
#endif
#if defined(RANRYU_SUBPARTICLES) && !defined(RANRYU_SPLATTED)
// Sub-particles (splat_subparticles.comp): parents split by the spawn pass are left out of the gather
// (their children stand for them), and the children's fixed-point splat is added, then reset to 0.
layout(std430) readonly buffer SubparticleLevels { uint sub_level[]; };
#endif

#include "../sim/grid.glsl"
#include "../sim/kernel.glsl"

#include "cell_run.glsl"

void main() {
    uvec3 node = gl_GlobalInvocationID;
    uvec3 dims = surface_grid.dims.xyz;
    if (any(greaterThanEqual(node, dims))) return;
    uint index = node.x + dims.x * (node.y + dims.y * node.z);
#ifdef RANRYU_SPLATTED
    phi[index] = float(splat[index]) * (1.0 / RANRYU_SUBPARTICLE_SPLAT_SCALE) - surface.iso;
    splat[index] = 0u;
#else
    vec3 x = surface_grid.origin.xyz + surface_grid.origin.w * vec3(node);
    float r = surface.kernel_radius, reach = r + surface.search_margin;
    ivec3 lo = grid_cell(x - reach), hi = grid_cell(x + reach);
    float sum = 0.0;
    for (int cz = lo.z; cz <= hi.z; ++cz)
        for (int cy = lo.y; cy <= hi.y; ++cy)
            for (int cx = lo.x; cx <= hi.x; ++cx) {
                uvec2 run = cell_run(cell_key(ivec3(cx, cy, cz)));
                for (uint j = run.x; j < run.y; ++j) {
#if defined(RANRYU_SUBPARTICLES)
                    if ((sub_level[j] >> RANRYU_SUBPARTICLE_SPLIT_SHIFT) != 0u) continue;
#endif
                    sum += kernel_w(length(x - sorted_position[j].xyz), r);
                }
            }
#ifdef RANRYU_SUBPARTICLES
    float children = float(splat[index]) * (1.0 / RANRYU_SUBPARTICLE_SPLAT_SCALE);
    splat[index] = 0u;
    phi[index] = (surface.volume * sum + children) - surface.iso;
#else
    phi[index] = surface.volume * sum - surface.iso;
#endif
#endif
}
