#version 430
// The substep's prediction, "pbf.predict" (docs/PBF.md (P1), (P10)), per particle, in place:
//     Start_i ← x_i,   x_i ← x_i + dt (v_i + dt (a_i + w a^p_i)),
// a_i the non-pressure accelerations (gravity, and what the last step's hooks added: the first lambda
// pass of each step writes gravity in the new cell order, the hooks add to it). The velocities are
// left as they are: v_n, which the wavelet analysis reads after the first lambda pass; (P7) replaces
// them at the step's end. The predicted position is projected as the step's end is (docs/SPH.md (8),
// along the path from x_i: motion.glsl), so that the iterations start with every particle in the tank
// and out of the obstacles, however far the fixed step carried it (Macklin & Müller's collision
// response on the prediction).
#include "pbf.glsl"

layout(local_size_x = 256) in;
layout(std430) buffer Positions { vec4 position[]; };
layout(std430) readonly buffer Velocities { vec4 velocity[]; };
layout(std430) readonly buffer Accelerations { vec4 accel[]; };
layout(std430) writeonly buffer Start { vec4 start[]; };
#ifdef RANRYU_PBF_WARM
// In: a^p_i of the last step (P10). Out: the displacement the step predicts without the warm start,
// x*_i − x_i − w a^p_i dt², which update_velocities.comp subtracts from the step's.
layout(std430) buffer PbfWarm { vec4 warm[]; };
#endif

#include "../fluid/motion.glsl"

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= sph.particle_count) return;   // no barriers in this pass
    float dt = step.dt;
    vec4 x = position[i];
    start[i] = x;
    if (parked(x)) return;   // it waits where it is (the emitter's reserve, fluid.glsl)
    vec3 a = accel[i].xyz;
#ifdef RANRYU_PBF_WARM
    vec3 push = pbf.warm_start * warm[i].xyz * dt * dt;
    a += pbf.warm_start * warm[i].xyz;
#endif
    vec3 v = velocity[i].xyz + dt * a, xstar = x.xyz + dt * v;
    keep_out_of_obstacles(x.xyz, xstar, v);
    keep_in_tank(x.xyz, xstar, v);
    position[i] = vec4(xstar, x.w);
#ifdef RANRYU_PBF_WARM
    warm[i] = vec4(xstar - x.xyz - push, 0.0);
#endif
}
