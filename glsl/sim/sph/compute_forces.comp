#version 430
// Acceleration of every fluid particle (docs/SPH.md eqs. (4), (5)) plus gravity:
//     a_i = g - sum_j m (p_i/rho_i^2 + p_j/rho_j^2) gradW_ij - sum_b psi_b (p_i/rho_i^2) gradW_ib
//           + 10 nu sum_j (2m/(rho_i + rho_j)) (v_ij . x_ij) / (|x_ij|^2 + 0.01 h^2) gradW_ij.
// Input: sorted positions, velocities, density (rho, p, p/rho^2). Output: accel[i].xyz.
// Records the substep's max |a| for the time step (eq. (7)).
#include "sph_common.glsl"

layout(local_size_x = 128) in;
layout(std430, binding = RANRYU_SSBO_POSITION) readonly buffer Positions { vec4 position[]; };
layout(std430, binding = RANRYU_SSBO_VELOCITY) readonly buffer Velocities { vec4 velocity[]; };
layout(std430, binding = RANRYU_SSBO_DENSITY) readonly buffer Density { vec4 density[]; };
layout(std430, binding = RANRYU_SSBO_ACCEL) writeonly buffer Accel { vec4 accel[]; };

void main() {
    uint i = gl_GlobalInvocationID.x;
    bool live = i < sph.particle_count;   // no early return: workgroup_max() has barriers
    float magnitude = 0.0;
    if (live) {
        vec3 xi = position[i].xyz;
        vec3 vi = velocity[i].xyz;
        vec3 di = density[i].xyz;
        float pi_term = di.z;
        float h = sph.h, h2 = h * h;
        float eps = 0.01 * h * h;
        vec3 a_pressure = vec3(0.0), a_viscous = vec3(0.0), a_wall = vec3(0.0);
        ivec3 c = grid_cell(xi);
        FOR_EACH_RUN {
            uvec2 run = NEIGHBOUR_RUN(c, true);
            for (uint j = run.x; j < run.y; ++j) {
                vec3 d = xi - position[j].xyz;
                float r2 = dot(d, d);
                if (r2 >= h2 || j == i) continue;   // before the square root: most candidates lie outside h
                float r = sqrt(r2);
                vec3 g = kernel_grad(d, r, h);
                vec3 dj = density[j].xyz;
                a_pressure -= (pi_term + dj.z) * g;
                a_viscous += (2.0 * dot(vi - velocity[j].xyz, d) / ((r2 + eps) * (di.x + dj.x))) * g;
            }
            run = NEIGHBOUR_RUN(c, false);
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
