#version 430
// "dfsph.coarse.prolong" (docs/DFSPH.md (D12)): each fluid particle takes the coarse correction at
// its position, trilinear between the centres of the eight coarse cells around it (an air cell's e
// is 0; a solid cell drops out and the weights of the others are renormalised: the wall's zero
// gradient), and kappa_i ← max(kappa_i + e(x_i), 0); with RANRYU_BOUNDARY_ROWS each of the step's
// boundary rows likewise, kappa_b ← max(kappa_b + e(x_b), 0) (D9): a wall that kept its pressure while
// the fluid beside it took the correction would pull the fluid's first layer to it. Dispatched like
// the residual pass, from the solve's indirect arguments (the fluid's workgroups, then the rows'), so
// it does nothing once the solve has converged. The lists open empty for the next solve.
#include "dfsph.glsl"
#include "coarse.glsl"

layout(local_size_x = 128) in;
layout(std430) readonly buffer Positions { vec4 position[]; };
layout(std430) buffer Kappa { float kappa[]; };
layout(std430) readonly buffer PressureAccel { vec4 pressure_accel[]; };   // w: the source s_i
layout(std430) readonly buffer Solve { SolveState solve; };
layout(std430) readonly buffer CoarseCell { vec4 coarse[]; };
layout(std430) buffer CoarseList { uvec2 coarse_count; uint coarse_capacity; uint coarse_pad; uint coarse_list[]; };
#ifdef RANRYU_BOUNDARY_ROWS
layout(std430) readonly buffer BoundaryList { uint boundary_list[]; };
layout(std430) readonly buffer BoundaryRows { BoundaryRowsState rows; };
#endif

// e at x: the trilinear interpolation over the cells that are not solid.
float correction_at(vec3 x) {
    vec3 u = (x - grid.origin.xyz) / coarse_cell_size() - 0.5;
    ivec3 base = ivec3(floor(u));
    vec3 t = u - vec3(base);
    float sum = 0.0, weights = 0.0;
    for (int k = 0; k < 8; ++k) {
        ivec3 o = ivec3(k & 1, (k >> 1) & 1, k >> 2), c = base + o;
        if (!coarse_inside(c)) continue;
        vec4 cell = coarse[coarse_index(c)];
        if (coarse_solid(cell.z)) continue;
        vec3 w3 = mix(1.0 - t, t, vec3(o));
        float w = w3.x * w3.y * w3.z;
        weights += w;
        if (coarse_active(cell.z)) sum += w * cell.x;   // 0 in an air cell
    }
    return weights > 0.0 ? sum / weights : 0.0;
}

void main() {
    uint i = gl_GlobalInvocationID.x;   // no barriers in this pass
#ifdef RANRYU_BOUNDARY_ROWS
    if (gl_WorkGroupID.x >= dfsph.groups) {   // a workgroup of the rows
        uint k = i - dfsph.groups * gl_WorkGroupSize.x;
        if (k >= rows.rows) return;
        uint b = boundary_list[k] & ~kFreshRow;
        KAPPA_B(b, 0u) = max(KAPPA_B(b, 0u) + correction_at(boundary[b].xyz), 0.0);
        return;
    }
#endif
    if (i >= sph.particle_count) return;
    if (i == 0u) coarse_count = uvec2(0u);
    vec4 x = position[i];
    // A particle that separates from the fluid (the free surface, a splash: warm_start_drop()) takes
    // no correction: it is not held at rho0, and the coarse cells do not resolve where it sits.
    if (parked(x) || pressure_accel[i].w > warm_start_drop()) return;
    kappa[i] = max(kappa[i] + correction_at(x.xyz), 0.0);
}
