#version 430
// "dfsph.boundary.wall" (docs/DFSPH.md (D9)): the wall's own part of each boundary particle's density,
//     BoundaryWall[b] = Σ_b' psi_b' W_bb'        (b' over the boundary particles within h, b included)
// one invocation per boundary particle. It depends on the boundary alone, so the Dfsph computes it
// when the boundary is built (at start, and again after the paddle moves: Fluid::boundary_generation()),
// not in every step's prepare passes (prepare_boundary_rows.comp reads it).
#include "../fluid/fluid.glsl"

layout(local_size_x = 128) in;
layout(std430) writeonly buffer BoundaryWall { float wall[]; };

void main() {
    uint b = gl_GlobalInvocationID.x;
    if (b >= sph.boundary_count) return;
    vec3 xb = boundary[b].xyz;
    ivec3 c = grid_cell(xb);
    float h2 = sph.h * sph.h, sum = 0.0;
    FOR_EACH_RUN {
        uvec2 run = NEIGHBOUR_RUN(c, false);
        for (uint q = run.x; q < run.y; ++q) {
            vec3 d = xb - boundary[q].xyz;
            if (dot(d, d) < h2) sum += boundary[q].w * kernel_w(length(d));
        }
    }
    wall[b] = sum;
}
