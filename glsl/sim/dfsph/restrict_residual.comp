#version 430
// "dfsph.coarse.restrict" (docs/DFSPH.md (D12)): one invocation per coarse cell c, the eight
// neighbour-grid cells it covers. Its fluid particles' residuals e_i of the density solve's first
// iteration (CoarseResidual, correct_pressure.comp) average to r_c; its fluid fills the fraction
//     phi_c = n_fluid / max(N − n_boundary, 1)   of its open volume, N = (H/dx)^3 particles a full cell
// (the boundary particles sit on a lattice of pitch dx, each taking a fluid particle's room), and it becomes
//     active  (phi_c >= 1/2):  rhs_c = H^2 r_c / (rho0^2 dt^2), listed by colour
//     solid   (no fluid, but boundary particles, or its centre a quarter spacing or more outside the
//             guard's domain, the tank):
//             a wall, where the correction's gradient is zero; phi = −1
//     air     (otherwise):     the free surface's side, where the correction is zero
// Each cell's e starts at 0. The sum runs in the sorted order, so it is the same whatever the
// schedule; only the lists' order is not, and no result depends on it (red-black sweeps update one
// colour from the other's values). Does nothing once the solve has converged (its dispatch is 0).
#include "dfsph.glsl"
#include "coarse.glsl"

layout(local_size_x = 128) in;
layout(std430) readonly buffer Solve { SolveState solve; };
layout(std430) readonly buffer CoarseResidual { float residual[]; };
layout(std430) writeonly buffer CoarseCell { vec4 coarse[]; };
layout(std430) buffer CoarseList { uvec2 coarse_count; uint coarse_capacity; uint coarse_pad; uint coarse_list[]; };

void main() {
    ivec3 n = coarse_dims();
    uint index = gl_GlobalInvocationID.x;
    if (solve.dispatch.x == 0u || index >= uint(n.x * n.y * n.z)) return;   // no barriers in this pass
    ivec3 c = coarse_cell_of(index);
    float sum = 0.0;
    uint count = 0u, walls = 0u;
    for (int dz = 0; dz < 2; ++dz)
        for (int dy = 0; dy < 2; ++dy)
            for (int dx = 0; dx < 2; ++dx) {
                ivec3 f = 2 * c + ivec3(dx, dy, dz);
                uvec2 run = cell_run(f, true);
                for (uint j = run.x; j < run.y; ++j) sum += residual[j];
                count += run.y - run.x;
                uvec2 wall = cell_run(f, false);
                walls += wall.y - wall.x;
            }
    float H = coarse_cell_size();
    if (count == 0u) {
        vec3 centre = grid.origin.xyz + (vec3(c) + 0.5) * H;
        vec3 margin = vec3(0.25 * sph.spacing);   // off the lattices that centres and bounds share
        bool outside = any(lessThan(centre, sph.domain_min.xyz - margin)) || any(greaterThan(centre, sph.domain_max.xyz + margin));
        coarse[index] = vec4(0.0, 0.0, walls > 0u || outside ? -1.0 : 0.0, 0.0);
        return;
    }
    float full = pow(H / sph.spacing, 3.0);
    float phi = float(count) / max(full - float(walls), 1.0);
    float rho_dt = sph.rest_density * step.dt;
    coarse[index] = vec4(0.0, H * H * (sum / float(count)) / (rho_dt * rho_dt), phi, 0.0);
    if (!coarse_active(phi)) return;
    uint colour = coarse_colour(c);
    uint slot = atomicAdd(coarse_count[colour], 1u);
    coarse_list[colour * coarse_capacity + slot] = index;
}
