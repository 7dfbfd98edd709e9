#version 430
// Vorticity confinement, "pbf.vorticity" (docs/PBF.md (P8)), in place on the velocities of the XSPH
// pass (it gathers only the neighbours' vorticity):
//     eta_i = Σ_j (m/rho_j) (|omega_j| − |omega_i|) ∇W_ij,   N_i = eta_i / |eta_i|,
//     v_i ← v_i + dt epsilon (N_i × omega_i),
// then the guard's records (motion.glsl): this pass ends the step.
#include "pbf.glsl"

layout(local_size_x = 128) in;
layout(std430) readonly buffer Positions { vec4 position[]; };
layout(std430) buffer Velocities { vec4 velocity[]; };
layout(std430) readonly buffer Density { vec4 density[]; };
layout(std430) readonly buffer Vorticity { vec4 vorticity[]; };

#include "../fluid/neighbours.glsl"
#include "../fluid/motion.glsl"

float size_i_;
vec3 eta_;
void visit_fluid(uint j, vec3 d, float r2) {
    eta_ += (sph.mass / density[j].x) * (vorticity[j].w - size_i_) * kernel_grad(d, sqrt(r2));
}
void visit_boundary(uint b, vec3 d, float r2) {}

void main() {
    uint i = gl_GlobalInvocationID.x;
    bool live = i < sph.particle_count;   // no early return: workgroup_max() has barriers
    uvec2 bits = uvec2(0u);
    if (live && !parked(position[i])) {   // a parked particle waits at rest (fluid.glsl)
        vec3 x = position[i].xyz;
        vec4 omega = vorticity[i];
        size_i_ = omega.w;
        eta_ = vec3(0.0);
        for_each_neighbour_around(i, x, sorted_cell(i), floatBitsToUint(density[i].w) & ~kBoundaryNear);
        float n = length(eta_);
        vec3 v = velocity[i].xyz;
        if (n > 0.0) v += step.dt * pbf.vorticity * cross(eta_ / n, omega.xyz);
        velocity[i] = vec4(v, 0.0);
        bits = record_particle(i, x, v);
    }
    record_maxima(bits, i);
}
