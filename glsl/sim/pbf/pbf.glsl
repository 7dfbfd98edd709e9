// What every PBF pass shares (docs/PBF.md; engine/sim/solvers/pbf.h): the fluid's blocks and the
// solver's constants. Its per-particle arrays, which each pass declares as it uses them:
//     Density         vec4 (rho_i (P2), p_i (P9), lambda_i (P4), flags) of the last lambda pass
//     Lambda          float: lambda_i (P4) of the current iteration, gathered by neighbours in (P6)
//     Start           vec4 per particle, carried with it through the reorder: x_n, the step's start (P1)
//     PbfVelocity     vec4: the velocity (x − x_n)/dt of (P7) before XSPH, gathered by neighbours
//     Vorticity       vec4: omega_i of (P8), gathered by neighbours (with vorticity confinement only)
//     PbfWarm         vec4 per particle, carried (warm_start > 0 only): a^p_i of (P10) between steps,
//                     the prediction's displacement d_i within one
#include "../fluid/fluid.glsl"

layout(std140, binding = RANRYU_UBO_PBF) uniform PbfBlock { PbfParams pbf; };

// The cell particle i was sorted into, that of its predicted position x*: the passes after the first
// lambda pass walk the runs around it (for_each_neighbour_around, neighbours.glsl) as that pass did,
// wherever the corrections have moved the particle since.
ivec3 sorted_cell(uint i) { return key_cell(sorted_keys[i]); }

#ifndef RANRYU_PBF_WALK   // the walk declares BoundaryNear itself (density_walk.glsl)
layout(std430) readonly buffer BoundaryNear { uint boundary_near[]; };

// A particle's flags for the walks after the first lambda pass: kBoundaryNear wherever its sorted
// cell has boundary particles in its 27 cells (flag_boundary_cells.comp), not only where the first
// pass found one within h, so that a particle the corrections carry towards a wall meets it.
uint walk_flags(uint i, uint flags) { return boundary_near[sorted_keys[i]] != 0u ? flags | kBoundaryNear : flags; }

#ifdef RANRYU_BOUNDARY_SKIN
layout(std430) readonly buffer MaskOrigins { vec4 mask_origin[]; };   // x* where the first lambda pass recorded the masks

// The boundary masks of the first lambda pass still hold every boundary particle within h of xi
// (neighbours.glsl): i has moved less than the skin since, |xi − x*| ≤ 0.99 kBoundarySkin h (the 1 %
// for the rounding of both tests), so a boundary particle within h of xi lay within h + skin of x*.
bool boundary_masks_hold(uint i, vec3 xi) {
    vec3 d = xi - mask_origin[i].xyz;
    float skin = 0.99 * kBoundarySkin * sph.h;
    return dot(d, d) <= skin * skin;
}
#endif
#endif
