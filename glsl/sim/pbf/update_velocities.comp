#version 430
// The step's velocities, "pbf.velocity" (docs/PBF.md (P7), first line), per particle: the last-resort
// projection of docs/SPH.md (8) on the corrected position x_i (from the step's start x_n, Start),
// then v_i = (x_i − x_n)/dt with the part into a solid removed. x_i is written back in place, v_i to
// PbfVelocity, which the XSPH pass gathers.
#include "pbf.glsl"

layout(local_size_x = 256) in;
layout(std430) buffer Positions { vec4 position[]; };
layout(std430) readonly buffer Start { vec4 start[]; };
layout(std430) writeonly buffer PbfVelocity { vec4 pbf_velocity[]; };

#include "../fluid/motion.glsl"

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= sph.particle_count) return;   // no barriers in this pass
    vec4 x = position[i];
    if (parked(x)) return;   // at rest where it waits (fluid.glsl)
    vec3 x0 = start[i].xyz, xi = x.xyz;
    vec3 v = (xi - x0) / step.dt;
    keep_out_of_obstacles(x0, xi, v);
    keep_in_tank(xi, v);
    position[i] = vec4(xi, x.w);
    pbf_velocity[i] = vec4(v, 0.0);
}
