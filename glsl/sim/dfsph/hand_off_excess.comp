#version 430
// The eliminated rows' residuals (docs/DFSPH.md (D13)), before each of the density solve's residual
// passes: the density change the fluid's pressure accelerations make at row b over the step, as (D9)'s,
//     r_b = dt² Σ_j m (0 − a_j)·gradW_bj − s_b          (s_b: BoundaryRow.x, the prepare pass's)
// and its excess handed to the fluid within h in proportion to the kernel,
//     q_b = (psi_b/m) max(r_b, 0) / Σ_j W_bj            into KAPPA_B(b, 1)
// so that the residual pass adds Σ_b W_ib q_b to particle i's residual. KAPPA_B(b, 1) is the divergence
// solve's kappa_v,b, free during the density solve (the next divergence solve starts its rows from none).
// One invocation a row; dispatched indirectly from the density solve's SolveState.rows_groups.
#include "dfsph.glsl"

layout(local_size_x = 128) in;
layout(std430) readonly buffer Positions { vec4 position[]; };
layout(std430) buffer Kappa { float kappa[]; };
layout(std430) readonly buffer PressureAccel { vec4 pressure_accel[]; };
layout(std430) readonly buffer BoundaryRow { vec2 row[]; };   // (s_b, 1/D_b), prepare_boundary_rows.comp
layout(std430) readonly buffer RowMasks { uint row_masks[]; };
#include "boundary_rows.glsl"

float change_, weight_;
void visit_row_fluid(uint j, vec3 d, float r) {
    change_ -= sph.mass * dot(pressure_accel[j].xyz, kernel_grad(d, r));
    weight_ += kernel_w(r);
}

void main() {
    uint k = gl_GlobalInvocationID.x;
    if (k >= rows.rows) return;   // no barriers in this pass
    uint b = boundary_list[k] & ~kFreshRow;
    change_ = weight_ = 0.0;
    for_each_fluid_near_row(boundary[b].xyz, k);
    float excess = max(step.dt * step.dt * change_ - row[k].x, 0.0);
    KAPPA_B(b, 1u) = weight_ > 0.0 ? boundary[b].w / sph.mass * excess / weight_ : 0.0;
}
