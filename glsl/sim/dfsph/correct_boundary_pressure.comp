#version 430
// A Jacobi iteration's boundary rows (docs/DFSPH.md (D9)), between the pressure accelerations and the
// fluid rows' "correct" pass, one invocation per row of the step: the density change the fluid's
// pressure accelerations make at the (immovable) boundary particle over the step,
//     delta_b = dt^2 Σ_j m (0 − a_j)·gradW_bj,
// the residual r_b = delta_b − s_b, and kappa_b ← max(kappa_b + omega_b r_b / (dt^2 D_b), 0).
// Once the solve has converged (its dispatch set to zero by the last "correct" pass) it does nothing,
// as the fluid's passes of the iterations issued beyond it. Dispatched indirectly from BoundaryRows.
#include "dfsph.glsl"

layout(local_size_x = 128) in;
layout(std430) readonly buffer Positions { vec4 position[]; };
layout(std430) readonly buffer PressureAccel { vec4 pressure_accel[]; };
layout(std430) readonly buffer BoundaryRow { vec2 row[]; };
layout(std430) readonly buffer Solve { SolveState solve; };
layout(std430) buffer Kappa { float kappa[]; };   // after the fluid's: kappa_b (D9)

#include "boundary_rows.glsl"

float change_;
void visit_row_fluid(uint j, vec3 d, float r) { change_ -= sph.mass * dot(pressure_accel[j].xyz, kernel_grad(d, r, sph.h)); }

void main() {
    uint k = gl_GlobalInvocationID.x;
    if (k >= rows.rows || solve.dispatch.x == 0u) return;   // no barriers in this pass
    uint b = boundary_list[k] & ~kFreshRow, s = solve.solve;
    change_ = 0.0;
    for_each_fluid_near(boundary[b].xyz);
    vec2 rw = row[k];
    float dt2 = step.dt * step.dt;
    float residual = dt2 * change_ - rw.x;
    KAPPA_B(b, s) = max(KAPPA_B(b, s) + dfsph.boundary_relaxation * residual * rw.y / dt2, 0.0);
}
