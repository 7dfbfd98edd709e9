#version 430
// The step's velocities, "pbf.velocity" (docs/PBF.md (P7), first line), per particle: the last-resort
// projection of docs/SPH.md (8) on the corrected position x_i (from the step's start x_n, Start),
// then v_i = (x_i − x_n)/dt with the part into a solid removed. x_i is written back in place, v_i to
// PbfVelocity, which the XSPH pass gathers. With the warm start (P10), the step's pressure acceleration
//     a^p_i = clamp_{RANRYU_PBF_WARM_CAP |g|}((x_i − x_n − d_i)/dt²)   where the last lambda pass found C_i > 0, else 0,
// d_i the displacement predict_positions.comp left in PbfWarm, x_i before the projection: what the
// warm start and the corrections moved the particle by, over dt², its length at most RANRYU_PBF_WARM_CAP |g|.
#include "pbf.glsl"

layout(local_size_x = 256) in;
layout(std430) buffer Positions { vec4 position[]; };
layout(std430) readonly buffer Start { vec4 start[]; };
layout(std430) writeonly buffer PbfVelocity { vec4 pbf_velocity[]; };
#ifdef RANRYU_PBF_WARM
layout(std430) readonly buffer Density { vec4 density[]; };
layout(std430) buffer PbfWarm { vec4 warm[]; };
#endif

#include "../fluid/motion.glsl"

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= sph.particle_count) return;   // no barriers in this pass
    vec4 x = position[i];
    if (parked(x)) return;   // at rest where it waits (fluid.glsl)
    vec3 x0 = start[i].xyz, xi = x.xyz;
    vec3 v = (xi - x0) / step.dt;
#ifdef RANRYU_PBF_WARM
    bool compressed = density[i].x > sph.rest_density;
    vec3 ap = compressed ? (xi - x0 - warm[i].xyz) / (step.dt * step.dt) : vec3(0.0);
    float cap = RANRYU_PBF_WARM_CAP * length(sph.gravity.xyz), size = length(ap);
    warm[i] = vec4(size > cap ? ap * (cap / size) : ap, 0.0);
#endif
    keep_out_of_obstacles(x0, xi, v);
    keep_in_tank(x0, xi, v);
    position[i] = vec4(xi, x.w);
    pbf_velocity[i] = vec4(v, 0.0);
}
