// The neighbours of a fluid particle, for the passes that run after a density pass on the same cell
// order and positions (the density pass found them and stored its flags and, with
// RANRYU_NEIGHBOUR_MASKS, its neighbour masks; engine/sim/fluid.h).
//
// Needs fluid.glsl and a `Positions` block (vec4 position[]) declared before it. The including pass
// defines the two visitors, which accumulate into the pass's own globals:
//     void visit_fluid(uint j, vec3 d, float r2);      // fluid j != i, d = x_i − x_j, r2 = |d|² < h²
//     void visit_boundary(uint b, vec3 d, float r2);   // boundary b,   d = x_i − x_b, r2 = |d|² < h²
//
// The masks: for the r-th run [s, e) of the walk, neighbours[2r·N + i] = s and neighbours[(2r+1)·N + i]
// holds bit j − s for each fluid j != i inside h (N = particle_count: consecutive particles store
// contiguously, and every invocation stores at the same run, so the stores coalesce). A neighbour 32 or
// more places into its run leaves the kMasksComplete flag clear, and the particle is walked instead.
// With RANRYU_BOUNDARY_MASKS (Fluid::boundary_masks(): sph.neighbour_masks, where they fit) the
// boundary's runs have masks too, after the fluid's: for the r-th run [s, e) of the boundary's walk,
// neighbours[2(R + r)·N + i] = s and neighbours[(2(R + r) + 1)·N + i] the bits b − s of the boundary
// particles within h (R = kNeighbourRuns), written where the particle's cell has boundary particles
// around it, and kBoundaryMasksComplete says they hold every one; a particle walks a boundary run only
// where that flag is clear. With RANRYU_BOUNDARY_SKIN (PBF, whose corrections move the particles
// between its walks) the boundary masks hold the boundary particles within h + skin of where the
// density pass found them (fluid.glsl kBoundarySkin); a walk reads them while the including solver's
// boundary_masks_hold(i, xi) says particle i has moved less than the skin since, and tests each
// against h: then every boundary particle within h of xi is among them, in the walk's order.
// A run's fluid neighbours come before its boundary ones, masked or walked.
// Either way the fluid neighbours come in the walk's order, so sums are the walk's bit for bit.
#ifdef RANRYU_NEIGHBOUR_MASKS
layout(std430) readonly buffer NeighbourMasks { uint neighbours[]; };
#endif

void visit_fluid(uint j, vec3 d, float r2);
void visit_boundary(uint b, vec3 d, float r2);
// A fluid neighbour's position; the including pass may define it to fetch more with it in one load
// (DFSPH's x_j with kappa_j: glsl/sim/dfsph/dfsph.glsl), as long as it is position[j].xyz.
#ifndef RANRYU_NEIGHBOUR_POSITION
#define RANRYU_NEIGHBOUR_POSITION(j) position[j].xyz
#endif
#ifdef RANRYU_BOUNDARY_SKIN
bool boundary_masks_hold(uint i, vec3 xi);
#endif

// The neighbours a run's mask holds, from `start`: fluid particles or boundary ones.
void visit_masked(vec3 xi, uint start, uint mask, bool fluid) {
    while (mask != 0u) {
        uint j = start + uint(findLSB(mask));
        mask &= mask - 1u;
        vec3 d = xi - (fluid ? RANRYU_NEIGHBOUR_POSITION(j) : boundary[j].xyz);
        if (fluid) visit_fluid(j, d, dot(d, d));
#ifdef RANRYU_BOUNDARY_SKIN
        else if (dot(d, d) < sph.h * sph.h) visit_boundary(j, d, dot(d, d));
#else
        else visit_boundary(j, d, dot(d, d));
#endif
    }
}

// Visits the fluid neighbours of particle i at xi, and its boundary neighbours when `flags` (its
// density[i].w bits) has kBoundaryNear; a particle without complete masks walks the runs around cell
// c, which is xi's cell for for_each_neighbour() (a pass that moves particles between the sort and
// its walk gives the cell they were sorted into, so that it walks what the density pass walked). A
// parked particle (the emitter's reserve, density_walk.glsl) has no neighbour.
void for_each_neighbour_around(uint i, vec3 xi, ivec3 c, uint flags) {
    if (parked(position[i])) return;
    float h2 = sph.h * sph.h;
    bool masked = false, walls = (flags & kBoundaryNear) != 0u, walls_masked = false;
#ifdef RANRYU_NEIGHBOUR_MASKS
    masked = (flags & kMasksComplete) != 0u;
#endif
#ifdef RANRYU_BOUNDARY_MASKS
    walls_masked = walls && (flags & kBoundaryMasksComplete) != 0u;
#endif
#ifdef RANRYU_BOUNDARY_SKIN
    walls_masked = walls_masked && boundary_masks_hold(i, xi);
#endif
    uint run_index = 0u;
    FOR_EACH_RUN {
        uint r = run_index++;
#ifdef RANRYU_NEIGHBOUR_MASKS
        if (masked) visit_masked(xi, neighbours[2u * r * sph.particle_count + i], neighbours[(2u * r + 1u) * sph.particle_count + i], true);
#endif
        uvec2 run = masked ? uvec2(0u) : NEIGHBOUR_RUN(c, true);   // ?: evaluates one side only
        for (uint j = run.x; j < run.y; ++j) {
            vec3 d = xi - RANRYU_NEIGHBOUR_POSITION(j);
            float r2 = dot(d, d);
            if (r2 >= h2 || j == i) continue;   // before the square root: most candidates lie outside h
            visit_fluid(j, d, r2);
        }
#ifdef RANRYU_BOUNDARY_MASKS
        uint w = kNeighbourRuns + r;   // the boundary's run r
        if (walls_masked) visit_masked(xi, neighbours[2u * w * sph.particle_count + i], neighbours[(2u * w + 1u) * sph.particle_count + i], false);
#endif
        run = walls && !walls_masked ? NEIGHBOUR_RUN(c, false) : uvec2(0u);
        for (uint b = run.x; b < run.y; ++b) {
            vec3 d = xi - boundary[b].xyz;
            float r2 = dot(d, d);
            if (r2 >= h2) continue;
            visit_boundary(b, d, r2);
        }
    }
}

void for_each_neighbour(uint i, vec3 xi, uint flags) { for_each_neighbour_around(i, xi, grid_cell(xi), flags); }
