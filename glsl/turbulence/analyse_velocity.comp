#version 430
// Wavelet analysis of the velocity at every fluid particle (docs/METHOD.md §3;
// engine/turbulence/wavelet.h states the choices and their reasons):
//
//     û_i = 1/ψ_sum,i · Σ_j (u_j − u_i) · ψ((x_i − x_j)/s),     ê_i = ½|û_i|²   (m/s, m²/s²)
//     ψ(x) = (3 − |x|²)·e^(−|x|²/2)          (3-D Mexican hat, −∇² of e^(−|x|²/2), zero mean)
//     ψ_sum,i = Σ_j |ψ((x_i − x_j)/s)|       (j = i included: ψ(0) = 3, so ψ_sum,i >= 3 > 0)
//
// both sums over the fluid particles j with |x_i − x_j| < R·s (R = truncation; R·s <= the grid's
// cell, so the 27 cells around x_i hold them all). u_j − u_i: a uniform velocity gives û_i = 0 exactly.
// Input: positions and velocities in cell order, the cell ranges and sorted keys of that order
// (fluid.glsl's fluid_run() tells stale ranges from current ones), GridParams, SphParams
// (particle_count, for fluid_run()), WaveletParams.
// Output: energy[i] = (û_i, ê_i) for i < particle_count.
// With RANRYU_NEIGHBOUR_RUNS (the density pass's run count), the candidates come from the density
// pass's neighbour masks (compute_density.comp) for the particles whose masks are complete: they hold
// every fluid j != i within h of x_i, a superset of the terms (R·s <= h), in the walk's order; the
// j = i term (ψ(0) = 3 to ψ_sum, 0 to the sum) is added first. The same terms, with ψ_sum summed in
// another order: within the reference's float bound either way (wavelet_test.cpp).
#include "../sim/fluid/fluid.glsl"

layout(local_size_x = 128) in;
layout(std430) readonly buffer Positions { vec4 position[]; };
layout(std430) readonly buffer Velocities { vec4 velocity[]; };
layout(std430) readonly buffer WaveletConstants { WaveletParams wavelet; };
layout(std430) writeonly buffer WaveletEnergy { vec4 energy[]; };
#ifdef RANRYU_NEIGHBOUR_RUNS
layout(std430) readonly buffer Density { vec4 density[]; };   // w: flags
layout(std430) readonly buffer NeighbourMasks { uint neighbours[]; };
#endif

// The 3-D Mexican hat at |x|² = q2.
float mexican_hat(float q2) { return (3.0 - q2) * exp(-0.5 * q2); }

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= wavelet.particle_count) return;   // no barriers in this pass
    vec3 xi = position[i].xyz;
    vec3 ui = velocity[i].xyz;
    float inv_s = 1.0 / wavelet.scale;
    float r2 = wavelet.truncation * wavelet.truncation;
    vec3 sum = vec3(0.0);
    float psi_sum = 0.0;
#ifdef RANRYU_NEIGHBOUR_RUNS
    if ((floatBitsToUint(density[i].w) & 1u) != 0u) {
        uint n = wavelet.particle_count;
        psi_sum = 3.0;   // j = i: |ψ(0)| = 3, and u_i − u_i = 0
        for (uint r = 0u; r < RANRYU_NEIGHBOUR_RUNS; ++r) {
            uint start = neighbours[2u * r * n + i], mask = neighbours[(2u * r + 1u) * n + i];
            while (mask != 0u) {
                uint j = start + uint(findLSB(mask));
                mask &= mask - 1u;
                vec3 d = (xi - position[j].xyz) * inv_s;
                float q2 = dot(d, d);
                if (q2 < r2) {
                    float psi = mexican_hat(q2);
                    sum += (velocity[j].xyz - ui) * psi;
                    psi_sum += abs(psi);
                }
            }
        }
        vec3 u_hat = sum / psi_sum;
        energy[i] = vec4(u_hat, 0.5 * dot(u_hat, u_hat));
        return;
    }
#endif
    ivec3 c = grid_cell(xi);
    FOR_EACH_RUN {
        uvec2 run = NEIGHBOUR_RUN(c, true);
        for (uint j = run.x; j < run.y; ++j) {
            vec3 d = (xi - position[j].xyz) * inv_s;
            float q2 = dot(d, d);
            if (q2 < r2) {
                float psi = mexican_hat(q2);
                sum += (velocity[j].xyz - ui) * psi;
                psi_sum += abs(psi);
            }
        }
    }
    vec3 u_hat = sum / psi_sum;
    energy[i] = vec4(u_hat, 0.5 * dot(u_hat, u_hat));
}
