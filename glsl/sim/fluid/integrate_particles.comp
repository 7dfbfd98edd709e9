#version 430
// Symplectic Euler (docs/SPH.md eq. (6)) with the substep's dt from the GPU (choose_time_step):
//     v_i += dt a_i,   x_i += dt v_i,
// then the last-resort projection of docs/SPH.md (8) and the guard's records (motion.glsl). A parked
// particle (fluid.glsl) stays as it is.
#include "fluid.glsl"

layout(local_size_x = 256) in;
layout(std430) buffer Positions { vec4 position[]; };
layout(std430) buffer Velocities { vec4 velocity[]; };
layout(std430) readonly buffer Accelerations { vec4 accel[]; };

#include "motion.glsl"

void main() {
    uint i = gl_GlobalInvocationID.x;
    bool live = i < sph.particle_count;   // no early return: workgroup_max() has barriers
    uvec2 bits = uvec2(0u);
    if (live && !parked(position[i])) {
        float dt = step.dt;
        vec3 x0 = position[i].xyz;
        vec3 v = velocity[i].xyz + dt * accel[i].xyz;
        vec3 x = x0 + dt * v;
        keep_out_of_obstacles(x0, x, v);
        keep_in_tank(x0, x, v);
        position[i] = vec4(x, position[i].w);
        velocity[i] = vec4(v, velocity[i].w);
        bits = record_particle(i, x, v);
    }
    record_maxima(bits, i);
}
