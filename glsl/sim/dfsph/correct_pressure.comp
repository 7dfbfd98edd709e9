#version 430
// A Jacobi iteration's second half (docs/DFSPH.md (D6)): the density change the pressure accelerations
// make over the step,
//     delta_i = dt^2 [Σ_j m (a_i − a_j)·gradW_ij + Σ_b psi_b a_i·gradW_ib],
// the residual r_i = delta_i − s_i, and the relaxed Jacobi update J_i = max(kappa_i + omega r_i factor_i / dt^2, 0);
// the density solve accelerates it (D10): from its iteration k = kChebyshevStart on,
//     kappa_i ← max(w_k (J_i − kappa_i^(k−1)) + kappa_i^(k−1), 0),
// w_k the Chebyshev weight of dfsph.chebyshev (SolveState.weight, dfsph.glsl), kappa^(k−1) the kappa the
// iteration before started from (KappaPrevious); otherwise kappa_i ← J_i. In the
// solve's first iteration a particle that separates from the fluid (warm_start_drop(), dfsph.glsl)
// drops its warm start first: the last step's pressure is a guess only where the fluid still holds
// together, and a stale one would throw a splash particle away as if it were still compressed.
// The iteration's mean error (1/N) Σ_i min(e_i/rho0, 1), N the particles not parked, e_i = max(r_i, 0)
// (the excess over rho0), or with dfsph.complementarity_error in the density solve e_i = |r_i| where
// the iteration's kappa_i > 0 (a particle that carries pressure must be at rho0, (D4)), is
// summed on the GPU: each workgroup adds its part in fixed point (units of 1/error_scale), and the last workgroup to finish decides.
// The iteration's largest min(e_i/rho0, 1), the peak, is taken beside it (each workgroup's by atomicMax
// on its float's bits); with dfsph.eta_peak > 0 the density solve has converged only once that is at
// most eta_peak too: a mean over N particles lets a compressed splash or impact of a few keep errors
// that grow with N at the same eta (docs/DFSPH.md (D6)). The density solve's last peak goes to the record.
// When the solve has converged (at least its minimum iterations, the error at most its eta) or has
// run the iterations the CPU issued, it sets the solve's dispatch to zero workgroups, so the
// iterations issued after it do no work, and adds the solve to the frame's record in StepState. The
// CPU issues the iterations and never waits for the decision. Dispatched indirectly from the
// SolveState's correct_groups: dfsph.groups workgroups over the fluid's particles, then with
// RANRYU_BOUNDARY_ROWS one invocation per boundary row of the step (docs/DFSPH.md (D9)), the rows'
// update of the same iteration: the density change the fluid's pressure accelerations make at the
// (immovable) boundary particle over the step,
//     delta_b = dt^2 Σ_j m (0 − a_j)·gradW_bj,
// the residual r_b = delta_b − s_b, and the l1-Jacobi update J_b = max(kappa_b + omega_b r_b / (dt^2 D_b), 0),
// which the density solve accelerates with the fluid's weight (D10): kappa_b ← max(w_k (J_b − kappa_b^(k−1))
// + kappa_b^(k−1), 0) from k = kChebyshevStart on, kappa_b^(k−1) kept after the fluid's in KappaPrevious.
// The two read the same accelerations and write different kappa, so one dispatch serves both (and
// one barrier, where two passes took two); the rows add nothing to the error, which is the fluid's.
// A density solve that ends sets the step the next ones may take from its iterations (D8).
// With RANRYU_ELIMINATED_ROWS the density solve's rows are no unknowns (docs/DFSPH.md (D13)): the solve
// dispatches the fluid's workgroups alone, and each particle's residual takes the excess the rows
// handed on before this pass, r_i ← r_i + Σ_b W_ib q_b (q_b in KAPPA_B(b, 1), free during the density
// solve: the divergence solve's rows start each step from none); its error is that residual's.
// With RANRYU_PRESSURE_STABILISATION the density solve's residual and diagonal blend in the compact
// Laplacian's (D12): r_i = dt² [(1 − gamma) Σ(...) + gamma l_i] − s_i, l_i = Density.y from the
// accelerate pass, and J_i = max(kappa_i + omega r_i / (dt² [(1 − gamma) D_i + gamma C_i]), 0),
// C_i = rho0 (Σ_j m c_ij + Σ_b psi_b c_ib), gamma = dfsph.stabilisation; the rows keep (D9)'s update.
#include "dfsph.glsl"

layout(local_size_x = 128) in;
layout(std430) readonly buffer Positions { vec4 position[]; };
layout(std430) readonly buffer Density { vec4 density[]; };
layout(std430) buffer Kappa { float kappa[]; };
layout(std430) readonly buffer PressureAccel { vec4 pressure_accel[]; };
// Not `coherent`: the workgroups add their parts by atomics and the one that decides reads them by
// atomics; the other fields are written by that one invocation and read by later dispatches, behind
// their barriers. Declared coherent, each invocation's reads of the iteration, the solve and the
// Chebyshev weight went past the cache: 2-3 % of a density iteration on the H200 (docs/PERFORMANCE.md
// "Passes within passes, timed apart"). Step (fluid.glsl) stays coherent, as measured: made not
// coherent too it gave 0.1 % more, measured while the frame's fastest particle was still written after
// an atomicMax (a race since removed: docs/PERFORMANCE.md "The frame's fastest and densest particles,
// without a race").
layout(std430) buffer Solve { SolveState solve; };
// The density solve's kappa^(k−1): the fluid's, then the rows' kappa_b^(k−1) by boundary particle.
layout(std430) buffer KappaPrevious { float kappa_previous[]; };

// The iteration's state from Solve. Contract: this pass reads Solve, kappa_i and kappa^(k−1) before its
// first store to Kappa or KappaPrevious, the order measured faster (docs/PERFORMANCE.md "The residual
// pass's reads before its stores").
struct Iteration {
    uint k;          // the solve's iterations so far
    uint s;          // 0: the density solve, 1: the divergence solve
    float weight;    // (D10)'s w_k
};
Iteration read_iteration() { return Iteration(solve.iterations, solve.solve, solve.weight); }

// (D10)'s step for the unknown at `slot` of KappaPrevious, whose kappa^(k−1) `before` was read there
// with the iteration's other reads: keeps the iterate this iteration started from (kappa) for the
// next, and from k = kChebyshevStart on returns max(w_k (J − kappa^(k−1)) + kappa^(k−1), 0) for the
// Jacobi update J, otherwise J.
float chebyshev_step(Iteration it, uint slot, float before, float kappa, float jacobi) {
    kappa_previous[slot] = kappa;
    return it.k >= kChebyshevStart ? max(it.weight * (jacobi - before) + before, 0.0) : jacobi;
}

#include "../fluid/neighbours.glsl"

#ifdef RANRYU_BOUNDARY_ROWS
layout(std430) readonly buffer BoundaryRow { vec2 row[]; };   // (s_b, 1/D_b), prepare_boundary_rows.comp
layout(std430) readonly buffer RowMasks { uint row_masks[]; };   // the prepare pass's (boundary_rows.glsl)
#include "boundary_rows.glsl"
float row_change_;
void visit_row_fluid(uint j, vec3 d, float r) { row_change_ -= sph.mass * dot(pressure_accel[j].xyz, kernel_grad(d, r)); }

// Row k's update (above).
void correct_row(uint k) {
    uint b = boundary_list[k] & ~kFreshRow;
    row_change_ = 0.0;
    for_each_fluid_near_row(boundary[b].xyz, k);
    Iteration it = read_iteration();
    uint slot = sph.particle_count + b;
    vec2 rw = row[k];
    float dt2 = step.dt * step.dt;
    float kappa_b = KAPPA_B(b, it.s), before = dfsph.chebyshev > 0.0 ? kappa_previous[slot] : 0.0;
    float residual = dt2 * row_change_ - rw.x;
    float next = max(kappa_b + dfsph.boundary_relaxation * residual * rw.y / dt2, 0.0);
    // (D10), as the fluid's: the rows and the fluid are one iteration
    if (it.s == 0u && dfsph.chebyshev > 0.0) next = chebyshev_step(it, slot, before, kappa_b, next);
    KAPPA_B(b, it.s) = next;
}
#endif

vec3 a_i_;
float change_, diagonal_;   // diagonal_: Σ_j m c_ij + Σ_b psi_b c_ib of (D12)
float handed_;   // (D13): Σ_b W_ib q_b, the rows' excess handed to particle i (hand_off_excess.comp)
void visit_fluid(uint j, vec3 d, float r2) {
    vec3 g = kernel_grad(d, sqrt(r2));
    change_ += sph.mass * dot(a_i_ - pressure_accel[j].xyz, g);
#ifdef RANRYU_PRESSURE_STABILISATION
    diagonal_ += sph.mass * compact_weight(d, g, r2);
#endif
}
void visit_boundary(uint b, vec3 d, float r2) {
    vec3 g = kernel_grad(d, sqrt(r2));
    change_ += boundary[b].w * dot(a_i_, g);
#ifdef RANRYU_PRESSURE_STABILISATION
    diagonal_ += boundary[b].w * compact_weight(d, g, r2);
#endif
#ifdef RANRYU_ELIMINATED_ROWS
    if (solve.solve == 0u) handed_ += kernel_w(sqrt(r2)) * KAPPA_B(b, 1u);   // (D13)
#endif
}

shared float wg_error_[gl_WorkGroupSize.x];
shared float wg_peak_[gl_WorkGroupSize.x];

// The last workgroup's decision, one invocation.
void decide() {
    uint total = atomicAdd(solve.error_sum, 0u);   // every workgroup added its part before counting itself
    // Over the particles not parked: a parked one has no neighbours, no residual (fluid.glsl).
    float mean = float(total) / (dfsph.error_scale * float(max(step.live_count, 1u)));
    float peak = uintBitsToFloat(atomicMax(solve.error_peak, 0u));
    solve.error_peak = 0u;
    solve.peak = peak;
    uint it = solve.iterations + 1u, s = solve.solve;
    solve.iterations = it;
    if (it > kChebyshevStart) solve.weight = next_chebyshev_weight(solve.weight);   // (D10): w_it
    uint least = s == 0u ? dfsph.min_iterations : 1u;
    uint cap = s == 0u ? dfsph.issued : dfsph.issued_divergence;
    bool converged = it >= least && mean <= (s == 0u ? dfsph.eta : dfsph.eta_divergence)
                     && (s != 0u || dfsph.eta_peak <= 0.0 || peak <= dfsph.eta_peak);
    if (converged || it >= cap) {
        solve.dispatch.x = 0u;
        solve.correct_groups = 0u;
        solve.rows_groups = 0u;
        step.iterations[s] += it;
        if (s == 0u) step.issued += dfsph.issued;
        else step.issued_divergence += dfsph.issued_divergence;
        step.iterations[s + 2u] = max(step.iterations[s + 2u], it);
        if (!converged) step.unconverged[s] += 1u;
        step.error[s] += mean;
        step.error[s + 2u] = max(step.error[s + 2u], mean);
        if (s == 0u) step.peak_error = max(step.peak_error, floatBitsToUint(peak));
        if (s == 0u && dfsph.shrink_step_above > 0u) step.iteration_dt = next_iteration_dt(step.stable_dt, it);
    }
    solve.error_sum = 0u;
    solve.groups_done = 0u;
}

void main() {
    uint i = gl_GlobalInvocationID.x, l = gl_LocalInvocationIndex;
    float error = 0.0;
#ifdef RANRYU_BOUNDARY_ROWS
    if (gl_WorkGroupID.x >= dfsph.groups) {   // a workgroup of the rows
        uint k = i - dfsph.groups * gl_WorkGroupSize.x;
        if (k < rows.rows) correct_row(k);
    } else
#endif
    if (i < sph.particle_count) {   // no early return: the workgroup sums below have barriers
        vec4 d = density[i], own = pressure_accel[i];
        a_i_ = own.xyz;
        change_ = 0.0;
        float factor = d.z;
        diagonal_ = 0.0;
        handed_ = 0.0;
#ifdef RANRYU_WALL_GRADIENT_AT
        // The boundary's part, Σ_b psi_b a_i . gradW_ib, as a_i . (Σ_b psi_b gradW_ib): the density pass's
        // sum (compute_density.comp), the same over the step's iterations; no boundary run is walked.
        for_each_neighbour(i, position[i].xyz, floatBitsToUint(d.w) & ~kBoundaryNear);
        change_ += dot(a_i_, pressure_accel[RANRYU_WALL_GRADIENT_AT * sph.particle_count + i].xyz);
#else
        for_each_neighbour(i, position[i].xyz, floatBitsToUint(d.w));
#endif
        // Every read before the first store (read_iteration()).
        Iteration it = read_iteration();
        float dt2 = step.dt * step.dt;
        float stored = KAPPA(i), before = dfsph.chebyshev > 0.0 ? kappa_previous[i] : 0.0;
#ifdef RANRYU_PRESSURE_STABILISATION
        if (it.s == 0u) {   // (D12)
            float gamma = dfsph.stabilisation;
            change_ = (1.0 - gamma) * change_ + gamma * d.y;
            float blended = (1.0 - gamma) / d.z + gamma * sph.rest_density * diagonal_;
            factor = d.z > 0.0 && blended > 0.0 ? 1.0 / blended : 0.0;
        }
#endif
        float residual = dt2 * change_ - own.w + handed_;   // handed_: (D13), 0 without it
        float kappa_i = it.k == 0u && own.w > warm_start_drop() ? 0.0 : stored;
        float next = max(kappa_i + dfsph.relaxation * residual * factor / dt2, 0.0);
        if (it.s == 0u && dfsph.chebyshev > 0.0) next = chebyshev_step(it, i, before, kappa_i, next);   // (D10): the density solve, when on
        KAPPA(i) = next;
        bool held = it.s == 0u && dfsph.complementarity_error != 0u && kappa_i > 0.0;
        error = clamp((held ? abs(residual) : residual) / sph.rest_density, 0.0, 1.0);
    }
    wg_error_[l] = error;
    wg_peak_[l] = error;
    barrier();
    for (uint half_ = gl_WorkGroupSize.x / 2u; half_ > 0u; half_ /= 2u) {
        if (l < half_) {
            wg_error_[l] += wg_error_[l + half_];
            wg_peak_[l] = max(wg_peak_[l], wg_peak_[l + half_]);
        }
        barrier();
    }
    if (l == 0u) {
        atomicAdd(solve.error_sum, uint(wg_error_[0] * dfsph.error_scale + 0.5));
        atomicMax(solve.error_peak, floatBitsToUint(wg_peak_[0]) & 0x7FFFFFFFu);   // -0.0 as 0
        memoryBarrierBuffer();
        if (atomicAdd(solve.groups_done, 1u) == gl_NumWorkGroups.x - 1u) decide();
    }
}
