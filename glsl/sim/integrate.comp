#version 430
// Integrates every particle over one substep (docs/METHOD.md §0, the talk's opening example) with the
// semi-implicit (symplectic) Euler step
//     u(t+dt) = u(t) + dt·a,        x(t+dt) = x(t) + dt·u(t+dt),
// which is exact for constant velocity and first-order accurate for u = a·t: it leads the analytic
// x = x0 + ½·a·t² by ½·a·t·dt. Walls: a particle that crosses a tank wall (inset by its radius) is
// put back on it and its normal velocity is reversed and scaled by the restitution.
#include "shared/bindings.h"

layout(local_size_x = 256) in;

layout(std430) buffer Positions { vec4 position[]; };
layout(std430) buffer Velocities { vec4 velocity[]; };
layout(std140, binding = RANRYU_UBO_SIM) uniform SimBlock { SimParams sim; };

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= sim.particle_count) return;
    vec3 u = velocity[i].xyz + sim.dt * sim.gravity.xyz;
    vec3 x = position[i].xyz + sim.dt * u;
    vec3 lo = sim.domain_min.xyz + sim.particle_radius;
    vec3 hi = sim.domain_max.xyz - sim.particle_radius;
    for (int a = 0; a < 3; ++a) {
        if (x[a] < lo[a]) { x[a] = lo[a]; u[a] = -sim.restitution * min(u[a], 0.0); }
        if (x[a] > hi[a]) { x[a] = hi[a]; u[a] = -sim.restitution * max(u[a], 0.0); }
    }
    position[i] = vec4(x, position[i].w);
    velocity[i] = vec4(u, velocity[i].w);
}
