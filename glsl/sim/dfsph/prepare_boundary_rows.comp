#version 430
// A solve's boundary rows, before its first pressure accelerations, "dfsph.boundary.prepare"
// (docs/DFSPH.md (D9)), one invocation per row of the step (BoundaryList):
//     rho*_b = Σ_j m W_bj + Σ_b' psi_b' W_bb' + dt Σ_j m (0 − v_j)·gradW_bj
//     s_b    = max(rho0, Σ_b' psi_b' W_bb') − rho*_b (density solve)
//            or −dt Σ_j m (0 − v_j)·gradW_bj (divergence solve)
// The wall's own part can read a little above rho0 deep inside it (the lattice's kernel sum is not
// exactly 1): no compression the fluid could relieve, and with a fluid neighbour at the edge of h
// (D_b → 0) it would ask for an unbounded kappa_b. So the rest density is at least the wall's own.
//     D_b    = psi_b Σ_j |gradW_bj| u_j            the l1 diagonal of (D9), u_j from the density pass
// Row[k] = (s_b, 1/D_b or 0). The density solve's kept kappa_b becomes its warm start: w·kappa_b, or
// none where the row is fresh (not a row the step before) or the particle separates from the wall
// (s_b above warm_start_drop(), as for the fluid (D6)). The divergence solve's starts from none (its
// first pressure accelerations come with the density pass, before the rows are listed).
// Velocities: v_n (divergence) or v* (density). The first invocation sizes the solve's residual pass
// (SolveState.correct_groups): the fluid's workgroups and the rows' (correct_pressure.comp); with
// RANRYU_ELIMINATED_ROWS the density solve's residual pass the fluid's alone, and the rows' passes of
// (D13) the rows' (SolveState.rows_groups). Their kappa_b's warm start is (D9)'s rule on the extension of
// the last step's final kappa, w·kappa_b, which the solve's first accelerations read (the extension of
// the fluid's warm start w·kappa_j would differ by (1 − w) times the hydrostatic offset).
// The wall's part Σ_b' psi_b' W_bb' depends on the boundary alone: compute_wall_density.comp keeps it in
// BoundaryWall, and this pass walks the fluid alone (docs/PERFORMANCE.md "The boundary rows' prepare
// passes").
#include "dfsph.glsl"

layout(local_size_x = 128) in;
layout(std430) readonly buffer Positions { vec4 position[]; };
layout(std430) readonly buffer Velocities { vec4 velocity[]; };
layout(std430) readonly buffer Accelerations { vec4 accel[]; };   // w: u_j
layout(std430) writeonly buffer BoundaryRow { vec2 row[]; };
layout(std430) buffer Solve { SolveState solve; };
layout(std430) buffer Kappa { float kappa[]; };   // after the fluid's: kappa_b (D9)
layout(std430) readonly buffer BoundaryWall { float wall[]; };   // Σ_b' psi_b' W_bb', per boundary particle

layout(std430) buffer RowMasks { uint row_masks[]; };   // recorded here (boundary_rows.glsl)
#define RANRYU_RECORD_ROW_MASKS 1
#include "boundary_rows.glsl"

float rho_, rate_, diagonal_;
void visit_row_fluid(uint j, vec3 d, float r) {
    vec3 g = kernel_grad(d, r);
    rho_ += sph.mass * kernel_w(r);
    rate_ -= sph.mass * dot(velocity[j].xyz, g);
    diagonal_ += length(g) * accel[j].w;
}

void main() {
    uint k = gl_GlobalInvocationID.x, s = solve.solve;
    if (k == 0u) {
#ifdef RANRYU_ELIMINATED_ROWS
        // (D13): the density solve's rows are no unknowns; their passes take the rows' workgroups
        if (s == 0u) {
            solve.correct_groups = dfsph.groups;
            solve.rows_groups = rows.dispatch.x;
        } else
#endif
        solve.correct_groups = dfsph.groups + rows.dispatch.x;
    }
    if (k >= rows.rows) return;   // no barriers in this pass
    uint entry = boundary_list[k], b = entry & ~kFreshRow;
    vec3 xb = boundary[b].xyz;
    rho_ = rate_ = diagonal_ = 0.0;
    // The step's first solve records the rows' masks; after the divergence solve the density solve's
    // prepare walks them (the positions have not moved since).
#ifdef RANRYU_DIVERGENCE_SOLVE
    if (s == 0u) for_each_fluid_near_row(xb, k); else
#endif
    for_each_fluid_near(xb, k);
    float w = wall[b];
    float source = s == 0u ? max(sph.rest_density, w) - (rho_ + w + step.dt * rate_) : -step.dt * rate_;
    float d_b = boundary[b].w * diagonal_;
    row[k] = vec2(source, d_b > 0.0 ? 1.0 / d_b : 0.0);
    bool drop = s == 1u || (entry & kFreshRow) != 0u || source > warm_start_drop();
    KAPPA_B(b, s) = drop ? 0.0 : dfsph.warm_start * KAPPA_B(b, s);
}
