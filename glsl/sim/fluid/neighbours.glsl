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
// Either way the fluid neighbours come in the walk's order, so sums are the walk's bit for bit.
#ifdef RANRYU_NEIGHBOUR_MASKS
layout(std430) readonly buffer NeighbourMasks { uint neighbours[]; };
#endif

void visit_fluid(uint j, vec3 d, float r2);
void visit_boundary(uint b, vec3 d, float r2);

// Visits the fluid neighbours of particle i at xi, and its boundary neighbours when `flags` (its
// density[i].w bits) has kBoundaryNear; a particle without complete masks walks the runs around cell
// c, which is xi's cell for for_each_neighbour() (a pass that moves particles between the sort and
// its walk gives the cell they were sorted into, so that it walks what the density pass walked). A
// parked particle (the emitter's reserve, density_walk.glsl) has no neighbour.
void for_each_neighbour_around(uint i, vec3 xi, ivec3 c, uint flags) {
    if (parked(position[i])) return;
    float h2 = sph.h * sph.h;
    bool masked = false, walls = (flags & kBoundaryNear) != 0u;
#ifdef RANRYU_NEIGHBOUR_MASKS
    masked = (flags & kMasksComplete) != 0u;
#endif
    uint run_index = 0u;
    FOR_EACH_RUN {
#ifdef RANRYU_NEIGHBOUR_MASKS
        if (masked) {
            uint start = neighbours[2u * run_index * sph.particle_count + i];
            uint mask = neighbours[(2u * run_index + 1u) * sph.particle_count + i];
            while (mask != 0u) {
                uint j = start + uint(findLSB(mask));
                mask &= mask - 1u;
                vec3 d = xi - position[j].xyz;
                visit_fluid(j, d, dot(d, d));
            }
        }
#endif
        ++run_index;
        uvec2 run = masked ? uvec2(0u) : NEIGHBOUR_RUN(c, true);   // ?: evaluates one side only
        for (uint j = run.x; j < run.y; ++j) {
            vec3 d = xi - position[j].xyz;
            float r2 = dot(d, d);
            if (r2 >= h2 || j == i) continue;   // before the square root: most candidates lie outside h
            visit_fluid(j, d, r2);
        }
        run = walls ? NEIGHBOUR_RUN(c, false) : uvec2(0u);
        for (uint b = run.x; b < run.y; ++b) {
            vec3 d = xi - boundary[b].xyz;
            float r2 = dot(d, d);
            if (r2 >= h2) continue;
            visit_boundary(b, d, r2);
        }
    }
}

void for_each_neighbour(uint i, vec3 xi, uint flags) { for_each_neighbour_around(i, xi, grid_cell(xi), flags); }
