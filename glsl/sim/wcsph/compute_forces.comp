#version 430
// WCSPH acceleration of every fluid particle (docs/SPH.md eqs. (4), (5), (5a)) plus gravity:
//     a_i = g - sum_j m (p_i/rho_i^2 + p_j/rho_j^2) gradW_ij - sum_b psi_b (p_i/rho_i^2) gradW_ib
//           + sum_j (10 nu + [v_ij . x_ij < 0] alpha c dx) (2m/(rho_i + rho_j)) (v_ij . x_ij) / (|x_ij|^2 + 0.01 h^2) gradW_ij.
// Input: sorted positions, velocities, density (rho, p, p/rho^2, flags) of i and the pair terms
// (rho, p/rho^2) of its neighbours, found as the density pass left them (neighbours.glsl).
// Output: accel[i].xyz. Records the substep's max |a| for the time step (eq. (7)).
#include "../fluid/fluid.glsl"

layout(local_size_x = 128) in;
layout(std430) readonly buffer Positions { vec4 position[]; };
layout(std430) readonly buffer Velocities { vec4 velocity[]; };
layout(std430) readonly buffer Density { vec4 density[]; };
layout(std430) writeonly buffer Accelerations { vec4 accel[]; };
layout(std430) readonly buffer PairTerms { vec2 pair_terms[]; };   // (rho_j, p_j/rho_j^2)

#include "../fluid/neighbours.glsl"

vec3 vi_, di_, a_pressure_, a_viscous_;
float nu_, nu_approach_, wall_;   // 10 nu; 10 nu + alpha c dx for an approaching pair ((5a)); p_i/(rho_i^2 m)

// One fluid pair's pressure and viscous terms (eqs. (4), (5), (5a)); a boundary pair's psi_b (p_i/rho_i^2)
// gradW_ib joins the pressure sum divided by m, as main() multiplies that sum by m. Two sums, not one
// for each term: with fewer values live the walk's loop keeps its loads in flight without spilling
// (docs/PERFORMANCE.md "WCSPH's forces pass and its registers").
void visit_fluid(uint j, vec3 d, float r2) {
    vec3 g = kernel_grad(d, sqrt(r2));
    vec2 tj = pair_terms[j];
    a_pressure_ -= (di_.z + tj.y) * g;
    float vx = dot(vi_ - velocity[j].xyz, d);
    float nu = vx < 0.0 ? nu_approach_ : nu_;
    a_viscous_ += (2.0 * nu * vx / ((r2 + 0.01 * sph.h * sph.h) * (di_.x + tj.x))) * g;
}

void visit_boundary(uint b, vec3 d, float r2) { a_pressure_ -= (wall_ * boundary[b].w) * kernel_grad(d, sqrt(r2)); }

void main() {
    uint i = gl_GlobalInvocationID.x;
    bool live = i < sph.particle_count;   // no early return: workgroup_max() has barriers
    float magnitude = 0.0;
    if (live) {
        vec4 density_i = density[i];
        vi_ = velocity[i].xyz;
        di_ = density_i.xyz;
        a_pressure_ = a_viscous_ = vec3(0.0);
        nu_ = 10.0 * sph.viscosity;
        nu_approach_ = nu_ + sph.artificial_viscosity * sph.sound_speed * sph.spacing;
        wall_ = di_.z / sph.mass;
        for_each_neighbour(i, position[i].xyz, floatBitsToUint(density_i.w));
        vec3 a = sph.gravity.xyz + sph.mass * (a_pressure_ + a_viscous_);
        accel[i] = vec4(a, 0.0);
        magnitude = length(a);
    }
    uvec2 m = workgroup_max(live ? max_bits(magnitude) : 0u, i);
    if (gl_LocalInvocationIndex == 0u) atomicMax(step.max_accel, m.x);
}
