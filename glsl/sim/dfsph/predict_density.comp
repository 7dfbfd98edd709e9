#version 430
// The density solve's start, "dfsph.pressure.predict" (docs/DFSPH.md (D4)): with v* the velocities
// after the divergence solve and the non-pressure step,
//     rho*_i = rho_i + dt Drho_i/Dt(v*),   s_i = rho0 − rho*_i,
// the warm start kappa_i = w·kappa of the last step (Warm.x) and its pressure accelerations (D3): the
// first iteration's first half. PressureAccel.w holds s_i; where positive, it tells the first iteration
// how far below rho0 the particle will be (D6's warm start). With RANRYU_PRESSURE_STABILISATION it also
// sums the warm start's compact Laplacian l_i into Density.y for the first iteration (D12; accelerate.comp).
#include "dfsph.glsl"

layout(local_size_x = 128) in;
layout(std430) readonly buffer Positions { vec4 position[]; };
layout(std430) readonly buffer Velocities { vec4 velocity[]; };
#ifdef RANRYU_PRESSURE_STABILISATION
layout(std430) buffer Density { vec4 density[]; };
#else
layout(std430) readonly buffer Density { vec4 density[]; };
#endif
layout(std430) readonly buffer Warm { vec2 warm[]; };
layout(std430) buffer Kappa { float kappa[]; };   // after the fluid's: kappa_b (D9)
layout(std430) buffer PressureAccel { vec4 pressure_accel[]; };   // w: the source; (D11)'s L_i after

#include "../fluid/neighbours.glsl"

vec3 vi_, a_;
float rate_, kappa_i_, compact_;
void visit_fluid(uint j, vec3 d, float r2) {
    vec3 g = kernel_grad(d, sqrt(r2));
    rate_ += sph.mass * dot(vi_ - velocity[j].xyz, g);
    float kj = dfsph.warm_start * warm[j].x;
    a_ -= sph.mass * (kappa_i_ + kj) * g;
#ifdef RANRYU_PRESSURE_STABILISATION
    compact_ += sph.mass * (kj - kappa_i_) * compact_weight(d, g, r2);
#endif
}
void visit_boundary(uint b, vec3 d, float r2) {
    vec3 g = kernel_grad(d, sqrt(r2));
    rate_ += boundary[b].w * dot(vi_, g);
    float kb = KAPPA_B(b, 0u);
    a_ -= (kappa_i_ + kb) * boundary[b].w * g;
#ifdef RANRYU_PRESSURE_STABILISATION
    compact_ += boundary[b].w * (kb - kappa_i_) * compact_weight(d, g, r2);
#endif
}

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= sph.particle_count) return;   // no barriers in this pass
    vec4 d = density[i];
    vi_ = velocity[i].xyz;
    kappa_i_ = dfsph.warm_start * warm[i].x;
    rate_ = 0.0;
    a_ = vec3(0.0);
    compact_ = 0.0;
    for_each_neighbour(i, position[i].xyz, floatBitsToUint(d.w));
    KAPPA(i) = kappa_i_;
#ifdef RANRYU_PRESSURE_STABILISATION
    density[i].y = sph.rest_density * compact_;   // (D12)
#endif
    pressure_accel[i] = vec4(CORRECTED(i, a_), sph.rest_density - (d.x + step.dt * rate_));
}
