#version 430
// The divergence solve's end and the non-pressure step (docs/DFSPH.md "A step"), in place:
//     v_i ← v_i + dt (a^p_i(kappa_v) + a_i),
// a^p of the solve's final kappa_v (D3) and a_i the non-pressure accelerations (D7, and what the
// step's hooks added). dt·kappa_v is kept in Warm.y for the next step's warm start (D5): the solve's
// impulse, which does not depend on the step as kappa_v (∝ 1/dt) does. Without
// RANRYU_DIVERGENCE_SOLVE: v_i ← v_i + dt a_i, and Warm.y = 0.
#ifdef RANRYU_DIVERGENCE_SOLVE
#define RANRYU_KAPPA_VEC4 1   // x_j with kappa_j, one load a neighbour (dfsph.glsl)
#endif
#include "dfsph.glsl"

layout(local_size_x = 128) in;
layout(std430) readonly buffer Positions { vec4 position[]; };
layout(std430) buffer Velocities { vec4 velocity[]; };
layout(std430) readonly buffer Density { vec4 density[]; };
layout(std430) readonly buffer Accelerations { vec4 accel[]; };
layout(std430) buffer Warm { vec2 warm[]; };
#ifdef RANRYU_GRADIENT_CORRECTION
layout(std430) readonly buffer PressureAccel { vec4 pressure_accel[]; };   // (D11)'s L_i, after the accelerations
#endif
#ifdef RANRYU_DIVERGENCE_SOLVE
layout(std430) readonly buffer Kappa { vec4 kappa4[]; };

#include "../fluid/neighbours.glsl"

float kappa_i_;
vec3 a_;
void visit_fluid(uint j, vec3 d, float r2) { a_ -= sph.mass * (kappa_i_ + kappa_j_) * kernel_grad(d, sqrt(r2)); }
void visit_boundary(uint b, vec3 d, float r2) { a_ -= (kappa_i_ + KAPPA_B(b, 1u)) * boundary[b].w * kernel_grad(d, sqrt(r2)); }
#endif

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= sph.particle_count) return;   // no barriers in this pass
    vec3 a = accel[i].xyz;
    float kappa_v = 0.0;
#ifdef RANRYU_DIVERGENCE_SOLVE
    kappa_i_ = kappa_v = KAPPA(i);
    a_ = vec3(0.0);
    for_each_neighbour(i, position[i].xyz, floatBitsToUint(density[i].w));
    a += CORRECTED(i, a_);   // (D11)
#endif
    velocity[i].xyz += step.dt * a;
    warm[i].y = step.dt * kappa_v;
}
