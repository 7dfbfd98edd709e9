#version 430
// A Jacobi iteration's first half (docs/DFSPH.md (D3), (D6)): the pressure accelerations of the kappa
// the last residual pass left,
//     a_i = −Σ_j m (kappa_i + kappa_j) gradW_ij − Σ_b psi_b (kappa_i + kappa_b) gradW_ib   (kappa_b: (D9)),
// times L_i with the gradient correction (D11). With RANRYU_PRESSURE_STABILISATION the density solve's
// iterations also sum the compact Laplacian of the same kappa into Density.y (D12):
//     l_i = rho0 Σ_j m (kappa_j − kappa_i) c_ij + rho0 Σ_b psi_b (kappa_b − kappa_i) c_ib.
// Dispatched indirectly from the solve's SolveState: zero workgroups once it has converged.
#define RANRYU_KAPPA_VEC4 1   // x_j with kappa_j from the Kappa block, one load a neighbour (dfsph.glsl)
#include "dfsph.glsl"

layout(local_size_x = 128) in;
layout(std430) readonly buffer Positions { vec4 position[]; };
#ifdef RANRYU_PRESSURE_STABILISATION
layout(std430) buffer Density { vec4 density[]; };
#else
layout(std430) readonly buffer Density { vec4 density[]; };
#endif
layout(std430) readonly buffer Kappa { vec4 kappa4[]; };
layout(std430) buffer PressureAccel { vec4 pressure_accel[]; };   // w: the source, kept
layout(std430) readonly buffer Solve { SolveState solve; };

#include "../fluid/neighbours.glsl"

float kappa_i_, compact_;
vec3 a_;
void visit_fluid(uint j, vec3 d, float r2) {
    float kj = kappa_j_;
    vec3 g = kernel_grad(d, sqrt(r2));
    a_ -= sph.mass * (kappa_i_ + kj) * g;
#ifdef RANRYU_PRESSURE_STABILISATION
    compact_ += sph.mass * (kj - kappa_i_) * compact_weight(d, g, r2);
#endif
}
void visit_boundary(uint b, vec3 d, float r2) {
    float kb = KAPPA_B(b, solve.solve);
    vec3 g = kernel_grad(d, sqrt(r2));
    a_ -= (kappa_i_ + kb) * boundary[b].w * g;
#ifdef RANRYU_PRESSURE_STABILISATION
    compact_ += boundary[b].w * (kb - kappa_i_) * compact_weight(d, g, r2);
#endif
}

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= sph.particle_count) return;   // no barriers in this pass
    kappa_i_ = KAPPA(i);
    a_ = vec3(0.0);
    compact_ = 0.0;
    for_each_neighbour(i, position[i].xyz, floatBitsToUint(density[i].w));
    pressure_accel[i].xyz = CORRECTED(i, a_);   // (D11)
#ifdef RANRYU_PRESSURE_STABILISATION
    if (solve.solve == 0u) density[i].y = sph.rest_density * compact_;   // (D12)
#endif
}
