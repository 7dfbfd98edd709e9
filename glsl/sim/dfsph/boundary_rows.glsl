// What the boundary-row passes share (docs/DFSPH.md (D9)): this step's rows, and the walk over a
// boundary particle's fluid neighbours. Needs dfsph.glsl and a `Positions` block before it; the
// including pass defines
//     void visit_row_fluid(uint j, vec3 d, float r);   // fluid j within h of x_b, d = x_b − x_j, r = |d|
layout(std430) readonly buffer BoundaryList { uint boundary_list[]; };
layout(std430) readonly buffer BoundaryRows { BoundaryRowsState rows; };

void visit_row_fluid(uint j, vec3 d, float r);

// The fluid particles within h of xb, in the grid's runs (no masks: those belong to fluid particles);
// parked ones (the emitter's reserve) are none.
void for_each_fluid_near(vec3 xb) {
    ivec3 c = grid_cell(xb);
    float h2 = sph.h * sph.h;
    FOR_EACH_RUN {
        uvec2 run = NEIGHBOUR_RUN(c, true);
        for (uint j = run.x; j < run.y; ++j) {
            vec4 xj = position[j];
            vec3 d = xb - xj.xyz;
            float r2 = dot(d, d);
            if (r2 < h2 && !parked(xj)) visit_row_fluid(j, d, sqrt(r2));
        }
    }
}
