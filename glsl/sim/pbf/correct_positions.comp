#version 430
// The position correction, "pbf.correct" (docs/PBF.md (P5), (P6)), a Jacobi step: every particle
// moves from the same positions,
//     dx_i = (1/rho0) [Σ_j m (lambda_i + lambda_j + s_corr(|x_ij|)) ∇W_ij + Σ_b psi_b lambda_i ∇W_ib],
//     s_corr(r) = −k dx² (W(r) / W(|dq|))^n,
// so the new positions go to the fluid's other buffer (NextPositions); the Pbf swaps them after.
// The fluid neighbours are those of the step's first lambda pass, the boundary particles those around
// the particle's sorted cell (walk_flags, pbf.glsl), from the first lambda pass's boundary masks while
// it stays within their skin (neighbours.glsl).
#include "pbf.glsl"

layout(local_size_x = 128) in;
layout(std430) readonly buffer Positions { vec4 position[]; };
layout(std430) writeonly buffer NextPositions { vec4 next_position[]; };
layout(std430) readonly buffer Density { vec4 density[]; };
layout(std430) readonly buffer Lambda { float lambda[]; };

#include "../fluid/neighbours.glsl"

// One sum for (P6)'s two: the wall's terms scaled by lambda_i/m, so the walk keeps one vector fewer live
// (docs/PERFORMANCE.md "WCSPH's forces pass and its registers").
float lambda_i_, wall_;   // wall_: lambda_i / m
vec3 sum_;
void visit_fluid(uint j, vec3 d, float r2) {
    float r = sqrt(r2);
    float s_corr = -pbf.s_corr_scale * pow(kernel_w(r) * pbf.inv_w_dq, pbf.s_corr_n);
    sum_ += (lambda_i_ + lambda[j] + s_corr) * kernel_grad(d, r);
}
void visit_boundary(uint b, vec3 d, float r2) { sum_ += (wall_ * boundary[b].w) * kernel_grad(d, sqrt(r2)); }

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= sph.particle_count) return;   // no barriers in this pass
    vec4 x = position[i];
    if (parked(x)) {   // no neighbours, no correction (fluid.glsl)
        next_position[i] = x;
        return;
    }
    lambda_i_ = lambda[i];
    wall_ = lambda_i_ / sph.mass;
    sum_ = vec3(0.0);
    for_each_neighbour_around(i, x.xyz, sorted_cell(i), walk_flags(i, floatBitsToUint(density[i].w)));
    next_position[i] = vec4(x.xyz + (sph.mass / sph.rest_density) * sum_, x.w);
}
