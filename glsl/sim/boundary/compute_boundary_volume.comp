#version 430
// Boundary particle weights (docs/SPH.md eq. (2); Akinci et al. 2012 eqs. 4-5), once at start:
//     psi_b = rho0 V_b,   V_b = min(1 / sum_b' W(x_b - x_b'), V_cell,b)   over boundary neighbours b', b included.
// The cap: boundary particles sit on lattices (engine/sim/boundary.cpp), where a surface particle's
// half-empty neighbourhood would make V_b = 1.18 V_cell and the fluid beside the wall 2.6 % too dense.
// V_cell,b is the volume of the lattice cell the particle stands for (<= dx^3: the sampling is never
// sparser than the fluid), which the sampling passes in w.
// Input: boundary particles (x_b, V_cell,b) sorted by cell, with their cell ranges.
// Output: weighted[b] = (x_b, psi_b), which the caller copies over the boundary array.
#include "../fluid/fluid.glsl"

layout(local_size_x = 128) in;
layout(std430) writeonly buffer Weighted { vec4 weighted[]; };   // (x_b, psi_b)

void main() {
    uint b = gl_GlobalInvocationID.x;
    if (b >= sph.boundary_count) return;
    vec3 xb = boundary[b].xyz;
    float sum = 0.0;
    ivec3 c = grid_cell(xb);
    FOR_EACH_RUN {
        uvec2 run = NEIGHBOUR_RUN(c, false);
        for (uint k = run.x; k < run.y; ++k) sum += kernel_w(length(xb - boundary[k].xyz));
    }
    float cell = boundary[b].w > 0.0 ? boundary[b].w : sph.spacing * sph.spacing * sph.spacing;
    weighted[b] = vec4(xb, sph.rest_density * min(1.0 / sum, cell));
}
