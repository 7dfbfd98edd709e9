#version 430
// Acceleration of every fluid particle (docs/SPH.md eqs. (4), (5)) plus gravity:
//     a_i = g - sum_j m (p_i/rho_i^2 + p_j/rho_j^2) gradW_ij - sum_b psi_b (p_i/rho_i^2) gradW_ib
//           + 10 nu sum_j (2m/(rho_i + rho_j)) (v_ij . x_ij) / (|x_ij|^2 + 0.01 h^2) gradW_ij.
// Input: sorted positions, velocities, density (rho, p, p/rho^2, flags) of i and the pair terms
// (rho, p/rho^2) of its neighbours. Output: accel[i].xyz.
// Records the substep's max |a| for the time step (eq. (7)).
// The density pass's flags (density[i].w, compute_density.comp) skip work: the boundary runs are walked
// only for particles with a boundary particle inside h, and with RANRYU_NEIGHBOUR_MASKS the fluid pairs
// come from the per-run masks when they are complete, in the order the walk meets them. The same pairs
// in the same order through the same add_pair(): the sums are the full walk's bit for bit.
#include "sph_common.glsl"

layout(local_size_x = 128) in;
layout(std430, binding = RANRYU_SSBO_POSITION) readonly buffer Positions { vec4 position[]; };
layout(std430, binding = RANRYU_SSBO_VELOCITY) readonly buffer Velocities { vec4 velocity[]; };
layout(std430, binding = RANRYU_SSBO_DENSITY) readonly buffer Density { vec4 density[]; };
layout(std430, binding = RANRYU_SSBO_ACCEL) writeonly buffer Accel { vec4 accel[]; };
layout(std430, binding = RANRYU_SSBO_PAIR_TERMS) readonly buffer PairTerms { vec2 pair_terms[]; };   // (rho_j, p_j/rho_j^2)
#ifdef RANRYU_NEIGHBOUR_MASKS
layout(std430, binding = RANRYU_SSBO_NEIGHBOURS) readonly buffer Neighbours { uint neighbours[]; };
#endif

// One fluid pair's pressure and viscous terms (eqs. (4), (5)), r2 = |d|² < h², j != i.
void add_pair(uint j, vec3 d, float r2, vec3 vi, vec3 di, float h, float eps, inout vec3 a_pressure, inout vec3 a_viscous) {
    float r = sqrt(r2);
    vec3 g = kernel_grad(d, r, h);
    vec2 tj = pair_terms[j];
    a_pressure -= (di.z + tj.y) * g;
    a_viscous += (2.0 * dot(vi - velocity[j].xyz, d) / ((r2 + eps) * (di.x + tj.x))) * g;
}

void main() {
    uint i = gl_GlobalInvocationID.x;
    bool live = i < sph.particle_count;   // no early return: workgroup_max() has barriers
    float magnitude = 0.0;
    if (live) {
        vec3 xi = position[i].xyz;
        vec3 vi = velocity[i].xyz;
        vec4 density_i = density[i];
        vec3 di = density_i.xyz;
        float pi_term = di.z;
        float h = sph.h, h2 = h * h;
        float eps = 0.01 * h * h;
        vec3 a_pressure = vec3(0.0), a_viscous = vec3(0.0), a_wall = vec3(0.0);
        ivec3 c = grid_cell(xi);
        uint flags = floatBitsToUint(density_i.w);
        bool masked = false, walls = (flags & 2u) != 0u;
#ifdef RANRYU_NEIGHBOUR_MASKS
        masked = (flags & 1u) != 0u;
#endif
        uint run_index = 0u;
        FOR_EACH_RUN {
#ifdef RANRYU_NEIGHBOUR_MASKS
            if (masked) {
                uint start = neighbours[2u * run_index * sph.particle_count + i];
                uint mask = neighbours[(2u * run_index + 1u) * sph.particle_count + i];
                while (mask != 0u) {
                    uint j = start + uint(findLSB(mask));
                    mask &= mask - 1u;
                    vec3 d = xi - position[j].xyz;
                    add_pair(j, d, dot(d, d), vi, di, h, eps, a_pressure, a_viscous);
                }
            }
#endif
            ++run_index;
            uvec2 run = masked ? uvec2(0u) : NEIGHBOUR_RUN(c, true);   // ?: evaluates one side only
            for (uint j = run.x; j < run.y; ++j) {
                vec3 d = xi - position[j].xyz;
                float r2 = dot(d, d);
                if (r2 >= h2 || j == i) continue;   // before the square root: most candidates lie outside h
                add_pair(j, d, r2, vi, di, h, eps, a_pressure, a_viscous);
            }
            run = walls ? NEIGHBOUR_RUN(c, false) : uvec2(0u);
            for (uint b = run.x; b < run.y; ++b) {
                vec3 d = xi - boundary[b].xyz;
                float r2 = dot(d, d);
                if (r2 >= h2) continue;
                a_wall -= boundary[b].w * kernel_grad(d, sqrt(r2), h);
            }
        }
        vec3 a = sph.gravity.xyz + sph.mass * (a_pressure + 10.0 * sph.viscosity * a_viscous) + pi_term * a_wall;
        accel[i] = vec4(a, 0.0);
        magnitude = length(a);
    }
    uvec2 m = workgroup_max(live ? max_bits(magnitude) : 0u, i);
    if (gl_LocalInvocationIndex == 0u) atomicMax(step.max_accel, m.x);
}
