#version 430
// Symplectic Euler (docs/SPH.md eq. (6)) with the substep's dt from the GPU (choose_time_step):
//     v_i += dt a_i,   x_i += dt v_i.
// Guard records (StepState): non-finite values, particles outside the domain, the frame's and the
// substep's max |v|; and the surge front, the largest x - domain_min.x among particles within
// sph.front_band of domain_min.y. Maxima go through workgroup reductions: one atomic a workgroup.
#include "sph_common.glsl"

layout(local_size_x = 256) in;
layout(std430, binding = RANRYU_SSBO_POSITION) buffer Positions { vec4 position[]; };
layout(std430, binding = RANRYU_SSBO_VELOCITY) buffer Velocities { vec4 velocity[]; };
layout(std430, binding = RANRYU_SSBO_ACCEL) readonly buffer Accel { vec4 accel[]; };

void main() {
    uint i = gl_GlobalInvocationID.x;
    bool live = i < sph.particle_count;   // no early return: workgroup_max() has barriers
    uint speed = 0u, front = 0u;
    if (live) {
        float dt = step.dt;
        vec3 v = velocity[i].xyz + dt * accel[i].xyz;
        vec3 x = position[i].xyz + dt * v;
        position[i] = vec4(x, position[i].w);
        velocity[i] = vec4(v, velocity[i].w);
        if (any(isnan(x)) || any(isinf(x)) || any(isnan(v)) || any(isinf(v))) {
            atomicAdd(step.nan_count, 1u);   // rare: an atomic each is fine
            atomicMin(step.nan_index, i);
        } else {
            if (any(lessThan(x, sph.domain_min.xyz)) || any(greaterThan(x, sph.domain_max.xyz))) {
                atomicAdd(step.escaped_count, 1u);
                atomicMin(step.escaped_index, i);
            }
            speed = max_bits(length(v));
            if (x.y - sph.domain_min.y < sph.front_band) front = max_bits(x.x - sph.domain_min.x);
        }
    }
    uvec2 s = workgroup_max(speed, i);
    uvec2 f = workgroup_max(front, i);
    if (gl_LocalInvocationIndex == 0u) {
        atomicMax(step.max_speed, s.x);
        if (s.x > atomicMax(step.frame_max_speed, s.x)) step.speed_index = s.y;
        atomicMax(step.front, f.x);
    }
}
