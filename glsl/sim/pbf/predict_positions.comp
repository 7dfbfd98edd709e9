#version 430
// The substep's prediction, "pbf.predict" (docs/PBF.md (P1)), per particle, in place:
//     Start_i ← x_i,   x_i ← x_i + dt (v_i + dt a_i),
// a_i the non-pressure accelerations (gravity, and what the last step's hooks added: the first lambda
// pass of each step writes gravity in the new cell order, the hooks add to it). The velocities are
// left as they are: v_n, which the wavelet analysis reads after the first lambda pass; (P7) replaces
// them at the step's end.
#include "pbf.glsl"

layout(local_size_x = 256) in;
layout(std430) buffer Positions { vec4 position[]; };
layout(std430) readonly buffer Velocities { vec4 velocity[]; };
layout(std430) readonly buffer Accelerations { vec4 accel[]; };
layout(std430) writeonly buffer Start { vec4 start[]; };

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= sph.particle_count) return;   // no barriers in this pass
    float dt = step.dt;
    vec4 x = position[i];
    start[i] = x;
    if (parked(x)) return;   // it waits where it is (the emitter's reserve, fluid.glsl)
    position[i] = vec4(x.xyz + dt * (velocity[i].xyz + dt * accel[i].xyz), x.w);
}
