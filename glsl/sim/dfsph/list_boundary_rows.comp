#version 430
// "dfsph.density" (its tail): every boundary particle within h of a fluid particle becomes a row of
// this step's solves (docs/DFSPH.md (D9)): listed once in BoundaryList (BoundaryMark[b] takes the
// step's epoch; the first to mark it appends it), with kFreshRow where it was not a row the step before.
// Runs after the density pass, over the fluid particles its flags mark as near a boundary.
#include "dfsph.glsl"

layout(local_size_x = 128) in;
layout(std430) readonly buffer Positions { vec4 position[]; };
layout(std430) readonly buffer Density { vec4 density[]; };
layout(std430) buffer BoundaryMark { uint boundary_mark[]; };
layout(std430) writeonly buffer BoundaryList { uint boundary_list[]; };
layout(std430) coherent buffer BoundaryRows { BoundaryRowsState rows; };

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= sph.particle_count || (floatBitsToUint(density[i].w) & kBoundaryNear) == 0u || parked(position[i])) return;   // no barriers
    vec3 xi = position[i].xyz;
    ivec3 c = grid_cell(xi);
    float h2 = sph.h * sph.h;
    uint epoch = rows.epoch;
    FOR_EACH_RUN {
        uvec2 run = NEIGHBOUR_RUN(c, false);
        for (uint b = run.x; b < run.y; ++b) {
            vec3 d = xi - boundary[b].xyz;
            if (dot(d, d) >= h2) continue;
            uint last = atomicExchange(boundary_mark[b], epoch);
            if (last != epoch) boundary_list[atomicAdd(rows.count, 1u)] = b | (last + 1u == epoch ? 0u : kFreshRow);
        }
    }
}
