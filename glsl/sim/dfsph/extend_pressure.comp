#version 430
// The eliminated rows' pressure (docs/DFSPH.md (D13)), before each of the density solve's accelerate
// passes and once after its last iteration: the fluid's kappa extended to each row of the step
// (BoundaryList), with the hydrostatic offset of Adami et al. taken only from fluid that carries pressure,
//     kappa_b = max(Σ_j W_bj (kappa_j + [kappa_j > 0] g·(x_b − x_j)/rho0) / Σ_j W_bj, 0),
// 0 where no fluid is within h, into KAPPA_B(b, 0): (D9)'s kappa_b, which the accelerate pass, the
// integration and the next step's warm start read. One invocation a row; dispatched indirectly from the
// density solve's SolveState.rows_groups (zero workgroups once it has converged), and after the solve
// from the rows' own dispatch (BoundaryRowsState).
#include "dfsph.glsl"

layout(local_size_x = 128) in;
layout(std430) readonly buffer Positions { vec4 position[]; };
layout(std430) buffer Kappa { float kappa[]; };
layout(std430) readonly buffer RowMasks { uint row_masks[]; };   // the prepare pass's (boundary_rows.glsl)
#include "boundary_rows.glsl"

float weight_, extended_;
void visit_row_fluid(uint j, vec3 d, float r) {
    float w = kernel_w(r), kj = KAPPA(j);
    weight_ += w;
    extended_ += w * (kj + (kj > 0.0 ? dot(sph.gravity.xyz, d) / sph.rest_density : 0.0));
}

void main() {
    uint k = gl_GlobalInvocationID.x;
    if (k >= rows.rows) return;   // no barriers in this pass
    uint b = boundary_list[k] & ~kFreshRow;
    weight_ = extended_ = 0.0;
    for_each_fluid_near_row(boundary[b].xyz, k);
    KAPPA_B(b, 0u) = weight_ > 0.0 ? max(extended_ / weight_, 0.0) : 0.0;
}
