// What the boundary-row passes share (docs/DFSPH.md (D9)): this step's rows, and the walk over a
// boundary particle's fluid neighbours. Needs dfsph.glsl and a `Positions` block before it; the
// including pass defines
//     void visit_row_fluid(uint j, vec3 d, float r);   // fluid j within h of x_b, d = x_b − x_j, r = |d|
// and declares the RowMasks block (uint row_masks[]) before it, writable where it records them
// (RANRYU_RECORD_ROW_MASKS).
layout(std430) readonly buffer BoundaryList { uint boundary_list[]; };
layout(std430) readonly buffer BoundaryRows { BoundaryRowsState rows; };

void visit_row_fluid(uint j, vec3 d, float r);

// The rows' neighbour masks, as the fluid's (fluid/neighbours.glsl): a row's walk tests some 200
// candidates for the 10-20 fluid particles within h, and the residual pass walks every row once an
// iteration. So the step's first prepare pass (prepare_boundary_rows.comp, with
// RANRYU_RECORD_ROW_MASKS) records for row k and the r-th run [s, e) of its walk row_masks[2r·B + k] = s
// and row_masks[(2r + 1)·B + k] = the bits j − s of the fluid j within h (B = sph.boundary_count, the
// most rows a step can have: consecutive rows store contiguously). A neighbour 32 or more places into
// its run marks the row incomplete (row_masks[k] = kIncompleteRow), and it is walked as before. The
// positions do not move between the density pass and the integration, so the masks hold through both
// solves (the residual passes and, after the divergence solve's, the density solve's prepare pass
// walk them); either way a row's neighbours come in the walk's order, so its sums are the walk's bit
// for bit.
const uint kIncompleteRow = 0xFFFFFFFFu;

// The fluid particles within h of xb (row k's), in the grid's runs; parked ones (the emitter's
// reserve) are none. With RANRYU_RECORD_ROW_MASKS it records row k's masks as it walks.
void for_each_fluid_near(vec3 xb, uint k) {
    ivec3 c = grid_cell(xb);
    float h2 = sph.h * sph.h;
    uint run_index = 0u;
    bool complete = true;
    FOR_EACH_RUN {
        uvec2 run = NEIGHBOUR_RUN(c, true);
        uint mask = 0u;
        for (uint j = run.x; j < run.y; ++j) {
            vec4 xj = position[j];
            vec3 d = xb - xj.xyz;
            float r2 = dot(d, d);
            if (r2 < h2 && !parked(xj)) {
                visit_row_fluid(j, d, sqrt(r2));
                if (j - run.x < 32u) mask |= 1u << (j - run.x);
                else complete = false;
            }
        }
#ifdef RANRYU_RECORD_ROW_MASKS
        row_masks[2u * run_index * sph.boundary_count + k] = run.x;
        row_masks[(2u * run_index + 1u) * sph.boundary_count + k] = mask;
#endif
        ++run_index;
    }
#ifdef RANRYU_RECORD_ROW_MASKS
    if (!complete) row_masks[k] = kIncompleteRow;
#endif
}

// Row k's fluid neighbours from its masks, or its walk where they are incomplete.
void for_each_fluid_near_row(vec3 xb, uint k) {
    uint b = sph.boundary_count;
    if (row_masks[k] == kIncompleteRow) {
        for_each_fluid_near(xb, k);
        return;
    }
    for (uint r = 0u; r < kNeighbourRuns; ++r) {
        uint start = row_masks[2u * r * b + k], mask = row_masks[(2u * r + 1u) * b + k];
        while (mask != 0u) {
            uint j = start + uint(findLSB(mask));
            mask &= mask - 1u;
            vec3 d = xb - position[j].xyz;
            visit_row_fluid(j, d, sqrt(dot(d, d)));
        }
    }
}
