#version 430
// The step's pair list, "dfsph.pairs" (docs/DFSPH.md (D12)): after the density pass, each fluid
// particle's neighbours within h, fluid and boundary, in the walk's order (neighbours.glsl), with the
// kernel gradient gradW_ij of docs/SPH.md (2) at the step's positions, into Pairs (layout:
// shared/bindings.h, RANRYU_PAIR_BOUNDARY). A particle with more than RANRYU_PAIR_SLOTS pairs stores
// its first that many and its full count, which tells the readers (pairs.glsl) to walk it instead; a
// parked particle has none.
#include "dfsph.glsl"

layout(local_size_x = 128) in;
layout(std430) readonly buffer Positions { vec4 position[]; };
layout(std430) readonly buffer Density { vec4 density[]; };
layout(std430) writeonly buffer Pairs { vec4 pairs[]; };

#include "../fluid/neighbours.glsl"

uint i_, count_;
void store(uint j, vec3 d, float r2) {
    if (count_ < uint(RANRYU_PAIR_SLOTS))
        pairs[(count_ + 1u) * sph.particle_count + i_] = vec4(kernel_grad(d, sqrt(r2), sph.h), uintBitsToFloat(j));
    ++count_;
}
void visit_fluid(uint j, vec3 d, float r2) { store(j, d, r2); }
void visit_boundary(uint b, vec3 d, float r2) { store(b | RANRYU_PAIR_BOUNDARY, d, r2); }

void main() {
    i_ = gl_GlobalInvocationID.x;
    if (i_ >= sph.particle_count) return;   // no barriers in this pass
    count_ = 0u;
    for_each_neighbour(i_, position[i_].xyz, floatBitsToUint(density[i_].w));
    pairs[i_] = vec4(0.0, 0.0, 0.0, uintBitsToFloat(count_));
}
