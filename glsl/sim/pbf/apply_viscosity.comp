#version 430
// XSPH viscosity, "pbf.viscosity" (docs/PBF.md (P7)), over the velocities of update_velocities.comp:
//     v_i ← v_i + c Σ_j (m/rho_j) (v_j − v_i) W_ij,
// into the fluid's Velocities. With RANRYU_PBF_VORTICITY the same walk computes the vorticity
//     omega_i = Σ_j (m/rho_j) ∇W_ij × (v_j − v_i)                                    (P8)
// into Vorticity, and confine_vorticity.comp ends the step; without it, this pass does: the guard's
// records (motion.glsl).
#include "pbf.glsl"

layout(local_size_x = 128) in;
layout(std430) readonly buffer Positions { vec4 position[]; };
layout(std430) writeonly buffer Velocities { vec4 velocity[]; };
layout(std430) readonly buffer Density { vec4 density[]; };
layout(std430) readonly buffer PbfVelocity { vec4 pbf_velocity[]; };
#ifdef RANRYU_PBF_VORTICITY
layout(std430) writeonly buffer Vorticity { vec4 vorticity[]; };
#endif

#include "../fluid/neighbours.glsl"
#include "../fluid/motion.glsl"

vec3 vi_, smooth_, curl_;
void visit_fluid(uint j, vec3 d, float r2) {
    float r = sqrt(r2), volume = sph.mass / density[j].x;
    vec3 vji = pbf_velocity[j].xyz - vi_;
    smooth_ += volume * kernel_w(r) * vji;
    curl_ += volume * cross(kernel_grad(d, r), vji);
}
void visit_boundary(uint b, vec3 d, float r2) {}

void main() {
    uint i = gl_GlobalInvocationID.x;
    bool live = i < sph.particle_count;   // no early return: workgroup_max() has barriers
    uvec2 bits = uvec2(0u);
    if (live && parked(position[i])) {
        velocity[i] = vec4(0.0);   // waits at rest (fluid.glsl)
    } else if (live) {
        vec3 x = position[i].xyz;
        vi_ = pbf_velocity[i].xyz;
        smooth_ = curl_ = vec3(0.0);
        // The walls add nothing to XSPH: their flag is cleared so the walk skips them.
        for_each_neighbour_around(i, x, sorted_cell(i), floatBitsToUint(density[i].w) & ~kBoundaryNear);
        vec3 v = vi_ + pbf.xsph * smooth_;
        velocity[i] = vec4(v, 0.0);
#ifdef RANRYU_PBF_VORTICITY
        vorticity[i] = vec4(curl_, length(curl_));
#else
        bits = record_particle(i, x, v);
#endif
    }
#ifndef RANRYU_PBF_VORTICITY
    record_maxima(bits, i);
#endif
}
