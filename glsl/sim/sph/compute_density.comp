#version 430
// Density and pressure of every fluid particle (docs/SPH.md eqs. (2), (3)):
//     rho_i = sum_j m W(x_i - x_j) + sum_b psi_b W(x_i - x_b),   p_i = max(0, B((rho_i/rho0)^7 - 1)).
// Input: sorted positions and keys, cell ranges of this substep, and the cells near the boundary
// (flag_boundary_cells.comp): elsewhere the boundary runs are not visited.
// Output: density[i] = (rho_i, p_i, p_i / rho_i^2, flags) and pair_terms[i] = (rho_i, p_i / rho_i^2):
// forces gathers the pair terms of its neighbours (8 bytes, not 16) and saves a division a pair, and
// reads the flags (the bits of a uint) to skip work:
//   bit 1: some boundary particle lies within h (forces walks the boundary runs only then);
//   bit 0, with RANRYU_NEIGHBOUR_MASKS: the masks below are complete. For the r-th run [s, e) of the
//     walk, neighbours[2r·N + i] = s and neighbours[(2r+1)·N + i] = the mask whose bit j − s is set
//     for each fluid j != i inside h (N = particle_count: consecutive particles store contiguously, and
//     every invocation stores at the same run, so the stores coalesce). A neighbour 32 or more places
//     into its run leaves bit 0 clear, and forces walks that particle's runs instead.
// Guard: the frame's largest rho/rho0 and a particle that has it.
#include "sph_common.glsl"

layout(local_size_x = 128) in;
layout(std430, binding = RANRYU_SSBO_POSITION) readonly buffer Positions { vec4 position[]; };
layout(std430, binding = RANRYU_SSBO_DENSITY) writeonly buffer Density { vec4 density[]; };
layout(std430, binding = RANRYU_SSBO_BOUNDARY_NEAR) readonly buffer Near { uint boundary_near[]; };
layout(std430, binding = RANRYU_SSBO_PAIR_TERMS) writeonly buffer PairTerms { vec2 pair_terms[]; };
#ifdef RANRYU_NEIGHBOUR_MASKS
layout(std430, binding = RANRYU_SSBO_NEIGHBOURS) writeonly buffer Neighbours { uint neighbours[]; };
#endif

void main() {
    uint i = gl_GlobalInvocationID.x;
    bool live = i < sph.particle_count;   // no early return: workgroup_max() has barriers
    float ratio = 0.0;
    if (live) {
        vec3 xi = position[i].xyz;
        ivec3 c = grid_cell(xi);
        float h = sph.h, h2 = h * h;
        float fluid = 0.0, wall = 0.0;
        uint flags = 0u, run_index = 0u;
        bool near_boundary = boundary_near[cell_key(c)] != 0u;   // else every boundary run below is empty
#ifdef RANRYU_NEIGHBOUR_MASKS
        flags = 1u;
#endif
        FOR_EACH_RUN {
            uvec2 run = NEIGHBOUR_RUN(c, true);
            uint mask = 0u;
            for (uint j = run.x; j < run.y; ++j) {   // |d|^2 first: most candidates lie outside h
                vec3 d = xi - position[j].xyz;
                float r2 = dot(d, d);
                if (r2 < h2) {
                    fluid += kernel_w(sqrt(r2), h);
                    uint bit = j - run.x;
                    if (j != i) {
                        if (bit < 32u) mask |= 1u << bit;
                        else flags &= ~1u;
                    }
                }
            }
#ifdef RANRYU_NEIGHBOUR_MASKS
            neighbours[2u * run_index * sph.particle_count + i] = run.x;
            neighbours[(2u * run_index + 1u) * sph.particle_count + i] = mask;
#endif
            ++run_index;
            run = near_boundary ? NEIGHBOUR_RUN(c, false) : uvec2(0u);
            for (uint b = run.x; b < run.y; ++b) {
                vec3 d = xi - boundary[b].xyz;
                float r2 = dot(d, d);
                if (r2 < h2) {
                    wall += boundary[b].w * kernel_w(sqrt(r2), h);
                    flags |= 2u;
                }
            }
        }
        float rho = sph.mass * fluid + wall;
        ratio = rho / sph.rest_density;
        float p = max(0.0, sph.stiffness * (pow(ratio, 7.0) - 1.0));
        float p_term = p / (rho * rho);
        density[i] = vec4(rho, p, p_term, uintBitsToFloat(flags));
        pair_terms[i] = vec2(rho, p_term);
    }
    uvec2 m = workgroup_max(live ? max_bits(ratio) : 0u, i);
    if (gl_LocalInvocationIndex == 0u && m.x > atomicMax(step.frame_max_density, m.x)) step.density_index = m.y;
}
