// The neighbours of a fluid particle for the DFSPH passes between the pair list and the step's end
// (docs/DFSPH.md (D12)): the positions do not move from the density pass to the integration, so every
// kernel gradient those passes take is the one list_pairs.comp stored, and a walk reads it instead of
// the cells, the masks and the positions. Needs dfsph.glsl and a `Positions` block before it; the
// including pass defines the two visitors, which accumulate into its own globals:
//     void visit_fluid_pair(uint j, vec3 g);      // fluid j != i within h, g = gradW_ij
//     void visit_boundary_pair(uint b, vec3 g);   // boundary b within h,   g = gradW_ib
// With RANRYU_PAIR_SLOTS a particle of at most that many pairs reads them from the Pairs block
// (layout: shared/bindings.h, RANRYU_PAIR_BOUNDARY); one with more, and every particle without it,
// walks its neighbours (neighbours.glsl) and takes the same gradients there. Either way the pairs come
// in the walk's order, so the sums are the walk's.
#ifdef RANRYU_PAIR_SLOTS
layout(std430) readonly buffer Pairs { vec4 pairs[]; };
#endif

#include "../fluid/neighbours.glsl"

void visit_fluid_pair(uint j, vec3 g);
void visit_boundary_pair(uint b, vec3 g);
void visit_fluid(uint j, vec3 d, float r2) { visit_fluid_pair(j, kernel_grad(d, sqrt(r2), sph.h)); }
void visit_boundary(uint b, vec3 d, float r2) { visit_boundary_pair(b, kernel_grad(d, sqrt(r2), sph.h)); }

// Visits particle i's pairs; `flags` are its density[i].w bits (for the walk).
void for_each_pair(uint i, uint flags) {
#ifdef RANRYU_PAIR_SLOTS
    uint count = floatBitsToUint(pairs[i].w);
    if (count <= uint(RANRYU_PAIR_SLOTS)) {
        for (uint k = 1u; k <= count; ++k) {
            vec4 p = pairs[k * sph.particle_count + i];
            uint j = floatBitsToUint(p.w);
            if ((j & RANRYU_PAIR_BOUNDARY) != 0u) visit_boundary_pair(j & ~RANRYU_PAIR_BOUNDARY, p.xyz);
            else visit_fluid_pair(j, p.xyz);
        }
        return;
    }
#endif
    for_each_neighbour(i, position[i].xyz, flags);
}
