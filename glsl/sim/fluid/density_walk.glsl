// The neighbour walk of a density pass (WCSPH's and DFSPH's): every candidate in the 27 cells (or 9
// merged rows) around particle i is tested against h, and with RANRYU_NEIGHBOUR_MASKS the ones inside
// are recorded as per-run masks for the passes after it, with RANRYU_BOUNDARY_MASKS the boundary's
// too, with RANRYU_BOUNDARY_SKIN those within h + skin (neighbours.glsl describes the layout).
//
// Needs fluid.glsl and a `Positions` block (vec4 position[]) declared before it. The including pass
// defines the visitors:
//     void visit_fluid(uint j, vec3 d, float r2);      // every fluid j within h, j == i included
//     void visit_boundary(uint b, vec3 d, float r2);   // every boundary b within h
// The boundary runs are walked only in cells that have a boundary particle in their 27 cells
// (flag_boundary_cells.comp, once at start).
layout(std430) readonly buffer BoundaryNear { uint boundary_near[]; };
#ifdef RANRYU_NEIGHBOUR_MASKS
layout(std430) writeonly buffer NeighbourMasks { uint neighbours[]; };
#endif

void visit_fluid(uint j, vec3 d, float r2);
void visit_boundary(uint b, vec3 d, float r2);

// Where a run's candidates within h are visited. By default inside the candidates' loop. With
// RANRYU_VISITS_FROM_HITS (a pass whose visits are heavy: DFSPH's density pass, PBF's lambda pass) the
// loop only tests |d|² and keeps the hits as bits, and visit_hits() visits them after it, in the same
// order: a warp's lanes test their candidates in step and most candidates lie outside h, so a visit
// inside the loop runs its arithmetic for almost every candidate with few lanes active, where from the
// bits a warp visits as many times as its lane with the most neighbours in the run (measured:
// docs/PERFORMANCE.md "The density pass's visits from its hits").
#ifdef RANRYU_VISITS_FROM_HITS
const bool kVisitsFromHits = true;
#else
const bool kVisitsFromHits = false;
#endif

// Visits run [s, e)'s candidates within h (r² < h2) in the run's order: those whose bit j − s is set in
// `hits` (the first 32), then any further ones, tested again (a run longer than 32 candidates is found
// where the fluid is compressed; a warp without one skips the second loop). Fluid candidates go to
// visit_fluid(), boundary ones to visit_boundary().
void visit_hits(vec3 xi, uvec2 run, uint hits, float h2, bool fluid) {
    for (; hits != 0u; hits &= hits - 1u) {
        uint j = run.x + uint(findLSB(hits));
        vec3 d = xi - (fluid ? position[j].xyz : boundary[j].xyz);
        if (fluid) visit_fluid(j, d, dot(d, d));
        else visit_boundary(j, d, dot(d, d));
    }
    for (uint j = run.x + 32u; j < run.y; ++j) {
        vec3 d = xi - (fluid ? position[j].xyz : boundary[j].xyz);
        float r2 = dot(d, d);
        if (r2 >= h2) continue;
        if (fluid) visit_fluid(j, d, r2);
        else visit_boundary(j, d, r2);
    }
}

// Walks particle i's neighbours; returns its flags (kMasksComplete, kBoundaryNear and
// kBoundaryMasksComplete of fluid.glsl) and in `count` how many neighbours it has within h, fluid
// (j != i) and boundary.
uint walk_neighbours(uint i, vec3 xi, out uint count) {
    ivec3 c = grid_cell(xi);
    float h2 = sph.h * sph.h, mask2 = h2;   // the boundary masks' radius squared
#ifdef RANRYU_BOUNDARY_SKIN
    mask2 = sph.h * sph.h * (1.0 + kBoundarySkin) * (1.0 + kBoundarySkin);
#endif
    uint flags = 0u, run_index = 0u;
    count = 0u;
    // A parked particle (fluid.glsl) has no neighbour but itself: nothing is within h of it, and the
    // crowd of parked ones in the grid's clamped bottom cells is not walked.
    if (parked(position[i])) {
        visit_fluid(i, vec3(0.0), 0.0);
        return flags;
    }
    bool near_boundary = boundary_near[cell_key(c)] != 0u;   // else every boundary run below is empty
#ifdef RANRYU_NEIGHBOUR_MASKS
    flags = kMasksComplete;
#endif
#ifdef RANRYU_BOUNDARY_MASKS
    flags |= kBoundaryMasksComplete;
#endif
    FOR_EACH_RUN {
        uvec2 run = NEIGHBOUR_RUN(c, true);
        uint mask = 0u, hits = 0u;
        for (uint j = run.x; j < run.y; ++j) {   // |d|² first: most candidates lie outside h
            vec3 d = xi - position[j].xyz;
            float r2 = dot(d, d);
            if (r2 < h2) {
                uint bit = j - run.x;
                if (!kVisitsFromHits) visit_fluid(j, d, r2);
                else if (bit < 32u) hits |= 1u << bit;
                if (j != i) {
                    ++count;
                    if (bit < 32u) mask |= 1u << bit;
                    else flags &= ~kMasksComplete;
                }
            }
        }
        if (kVisitsFromHits) visit_hits(xi, run, hits, h2, true);
#ifdef RANRYU_NEIGHBOUR_MASKS
        neighbours[2u * run_index * sph.particle_count + i] = run.x;
        neighbours[(2u * run_index + 1u) * sph.particle_count + i] = mask;
#endif
        run = near_boundary ? NEIGHBOUR_RUN(c, false) : uvec2(0u);
        uint boundary_mask = 0u;
        hits = 0u;
        for (uint b = run.x; b < run.y; ++b) {
            vec3 d = xi - boundary[b].xyz;
            float r2 = dot(d, d);
            if (r2 < h2) {
                if (!kVisitsFromHits) visit_boundary(b, d, r2);
                else if (b - run.x < 32u) hits |= 1u << (b - run.x);
                flags |= kBoundaryNear;
                ++count;
            }
            if (r2 < mask2) {
                if (b - run.x < 32u) boundary_mask |= 1u << (b - run.x);
                else flags &= ~kBoundaryMasksComplete;
            }
        }
        if (kVisitsFromHits) visit_hits(xi, run, hits, h2, false);
#ifdef RANRYU_BOUNDARY_MASKS
        if (near_boundary) {   // else kBoundaryNear stays clear and no walk reads them
            neighbours[2u * (kNeighbourRuns + run_index) * sph.particle_count + i] = run.x;
            neighbours[(2u * (kNeighbourRuns + run_index) + 1u) * sph.particle_count + i] = boundary_mask;
        }
#endif
        ++run_index;
    }
    return flags;
}
