#version 430
// WCSPH density and pressure of every fluid particle (docs/SPH.md eqs. (2), (3)):
//     rho_i = sum_j m W(x_i - x_j) + sum_b psi_b W(x_i - x_b),   p_i = max(0, B((rho_i/rho0)^7 - 1)).
// Input: sorted positions and keys, the cell ranges of this substep, the cells near the boundary.
// Output: density[i] = (rho_i, p_i, p_i / rho_i^2, flags) and pair_terms[i] = (rho_i, p_i / rho_i^2):
// forces gathers the pair terms of its neighbours (8 bytes, not 16) and saves a division a pair. The
// flags (fluid.glsl) and, with RANRYU_NEIGHBOUR_MASKS, the neighbour masks (density_walk.glsl) let
// the passes after it skip the candidate tests.
// Guard: the frame's largest rho/rho0 and a particle that has it (extremes.glsl).
#include "../fluid/fluid.glsl"

layout(local_size_x = 128) in;
#include "../fluid/extremes.glsl"
layout(std430) readonly buffer Positions { vec4 position[]; };
layout(std430) writeonly buffer Density { vec4 density[]; };
layout(std430) writeonly buffer PairTerms { vec2 pair_terms[]; };

#include "../fluid/density_walk.glsl"

float fluid_sum_, wall_sum_;
void visit_fluid(uint j, vec3 d, float r2) { fluid_sum_ += kernel_w(sqrt(r2)); }
void visit_boundary(uint b, vec3 d, float r2) { wall_sum_ += boundary[b].w * kernel_w(sqrt(r2)); }

void main() {
    uint i = gl_GlobalInvocationID.x;
    bool live = i < sph.particle_count;   // no early return: workgroup_max() has barriers
    float ratio = 0.0;
    if (live) {
        fluid_sum_ = 0.0;
        wall_sum_ = 0.0;
        uint count;
        uint flags = walk_neighbours(i, position[i].xyz, count);
        float rho = sph.mass * fluid_sum_ + wall_sum_;
        ratio = rho / sph.rest_density;
        float p = max(0.0, sph.stiffness * (pow(ratio, 7.0) - 1.0));
        float p_term = p / (rho * rho);
        density[i] = vec4(rho, p, p_term, uintBitsToFloat(flags));
        pair_terms[i] = vec2(rho, p_term);
    }
    uvec2 m = workgroup_max(live ? max_bits(ratio) : 0u, i);
    if (gl_LocalInvocationIndex == 0u && m.x != 0u) keep_extreme(RANRYU_EXTREME_DENSITY, m, position[m.y].xyz);
}
