#version 430
// "dfsph.density" (its tail), one invocation: the rows the density pass listed (compute_density.comp) become this step's
// (docs/DFSPH.md (D9)): the boundary passes' indirect dispatch covers them, and the list opens empty
// for the next step's density pass under a new epoch.
#include "dfsph.glsl"

layout(local_size_x = 1) in;
layout(std430) buffer BoundaryRows { BoundaryRowsState rows; };

// The boundary passes' workgroup size (prepare_boundary_rows.comp, correct_pressure.comp's rows;
// the Dfsph checks that both are built with it).
const uint kRowGroup = 128u;

void main() {
    uint n = rows.count;
    rows.rows = n;
    rows.count = 0u;
    rows.epoch += 1u;
    rows.dispatch = uvec4((n + kRowGroup - 1u) / kRowGroup, 1u, 1u, 0u);
}
