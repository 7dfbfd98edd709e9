// What every DFSPH pass shares (docs/DFSPH.md; engine/sim/solvers/dfsph.h): the fluid's blocks, the
// solver's constants, and its per-particle arrays, which each pass declares as it uses them:
//     Density         vec4 (rho_i, p_i of the last step, factor_i = 1/D_i (D2), flags); with
//                     RANRYU_PRESSURE_STABILISATION, y holds during the density solve the compact
//                     Laplacian's sum of (D12) for the kappa the iteration's accelerations read, and the
//                     integration writes the frame's pressure over it as before
//     Kappa           vec4 per particle (x_i, kappa_i): w the solve's current kappa_i = p_i/rho_i^2 (D3),
//                     xyz the particle's position, which the density pass writes and which holds until
//                     the integration (the positions do not move in between), so that a walk gathering
//                     kappa_j reads x_j with it, one load a neighbour (RANRYU_NEIGHBOUR_POSITION of
//                     neighbours.glsl); then, from float 4N on, the boundary rows' kappa_b (D9, below),
//                     padded to whole vec4s so that the vec4 view reads a row within the buffer.
//                     A pass declares it as `float kappa[]` and reads KAPPA(i), or, to gather x_j and
//                     kappa_j together, as `vec4 kappa4[]` with RANRYU_KAPPA_VEC4 defined before this file
//     KappaPrevious   float: the kappa_i the density solve's previous iteration started from (D10)
//     PressureAccel   vec4: xyz a^p_i (D3) of the current kappa, gathered by neighbours; w: the solve's
//                     source s_i of (D4) or (D5); w > warm_start_drop() drops the warm start; then,
//                     with RANRYU_GRADIENT_CORRECTION, two vec4 per particle: L_i of (D11); then, with
//                     RANRYU_WALL_GRADIENT_AT k, at k N + i the wall's gradient sum Σ_b psi_b gradW_ib
//                     (xyz) of the density pass, for the residual pass (correct_pressure.comp)
//     Warm            vec2 per particle, carried with it through every reorder: (kappa of the last
//                     density solve, dt·kappa_v of the last divergence solve: its impulse, which the
//                     next step divides by its own dt, docs/DFSPH.md below its table), the warm starts
//                     of (D6)
//     Solve           SolveState of the solve under way (shared/bindings.h); the Dfsph opens it (a copy
//                     of its initial state) before the pass that computes the solve's source
#include "../fluid/fluid.glsl"

layout(std140, binding = RANRYU_UBO_DFSPH) uniform DfsphBlock { DfsphParams dfsph; };

// 2(d + 2) of (D7), d = 3.
const float kViscosityFactor = 10.0;

// (D10): the density solve's Chebyshev acceleration starts at its iteration kChebyshevStart (counted
// from 0), and iteration k ≥ kChebyshevStart takes the weight w_k: w = 2/(2 − rho²) at the first, then
// w ← 4/(4 − rho² w), rho = dfsph.chebyshev (Wang 2015). The solve opens with the first in
// SolveState.weight (engine/sim/solvers/dfsph.cpp); next_chebyshev_weight() is the step from w_k to
// w_(k+1), which the residual pass's deciding invocation takes once an iteration.
const uint kChebyshevStart = 2u;
float next_chebyshev_weight(float w) { return 4.0 / (4.0 - dfsph.chebyshev * dfsph.chebyshev * w); }

// (D8): the step the density solve's iterations allow, from the step's stable dt and the iterations
// its density solve took: 0.9 times it after more than shrink_step_above, 1.1 times after fewer than
// grow_step_below, as it is between; within [iteration_dt_min, dt_max]. The CPU's mirror is
// sim::next_iteration_dt() (engine/sim/solvers/dfsph.h).
float next_iteration_dt(float stable_dt, uint iterations) {
    float f = iterations > dfsph.shrink_step_above ? 0.9 : iterations < dfsph.grow_step_below ? 1.1 : 1.0;
    return clamp(stable_dt * f, dfsph.iteration_dt_min, sph.dt_max);
}

// A particle whose predicted density change leaves it this far below rho0 (or that is deficient in
// neighbours) starts its solve from no pressure instead of the last step's (D6): 1 % of rho0 is
// separation (a splash, the free surface), far beyond the solve's own error, while the bulk of a
// resting column, within eta of rho0 either way, keeps its hydrostatic pressure.
float warm_start_drop() { return 0.01 * sph.rest_density; }

// The boundary rows of (D9): with RANRYU_BOUNDARY_ROWS each boundary particle b within h of the fluid
// has its own kappa_b, the density solve's kept from step to step (the walls do not move), after the
// fluid's in the Kappa block: its float 4 particle_count + 2b + s, s = 0 the density solve's, 1 the divergence
// solve's (with RANRYU_ELIMINATED_ROWS the density solve keeps its rows' q_b there, docs/DFSPH.md (D13)). A fluid
// particle pairs with it as with a fluid neighbour,
//     a_i −= psi_b (kappa_i + kappa_b) gradW_ib          (D3) with (D9)
// Without it kappa_b = 0: Akinci's boundary term, kappa_i once. KAPPA_B reads the pass's Kappa block.
#ifdef RANRYU_KAPPA_VEC4
#define KAPPA(i) kappa4[i].w
#define KAPPA_ROW_(k) kappa4[sph.particle_count + ((k) >> 2u)][(k) & 3u]
#else
#define KAPPA(i) kappa[4u * (i) + 3u]
#define KAPPA_ROW_(k) kappa[4u * sph.particle_count + (k)]
#endif
#ifdef RANRYU_BOUNDARY_ROWS
#define KAPPA_B(b, s) KAPPA_ROW_(2u * (b) + (s))
#else
#define KAPPA_B(b, s) 0.0
#endif

// A walk that gathers kappa_j (RANRYU_KAPPA_VEC4): x_j from the Kappa block with it, kappa_j kept in
// kappa_j_ for the visit_fluid() that follows.
#ifdef RANRYU_KAPPA_VEC4
float kappa_j_;
vec3 position_with_kappa(vec4 xk) {
    kappa_j_ = xk.w;
    return xk.xyz;
}
#define RANRYU_NEIGHBOUR_POSITION(j) position_with_kappa(kappa4[j])
#endif

// A listed row's entry in BoundaryList: the boundary particle's index, and this bit when it was not a
// row the step before (its kept kappa_b is stale, and its solve starts from none).
const uint kFreshRow = 0x80000000u;

// (D11), with RANRYU_GRADIENT_CORRECTION: the kernel-gradient correction L_i, symmetric, written by the
// density pass after the particles' accelerations in PressureAccel (a compute shader may have 16
// storage blocks on llvmpipe, and the density pass has them all): PressureAccel[n + 2i] = (L_xx, L_yy, L_zz, L_xy),
// PressureAccel[n + 2i + 1] = (L_xz, L_yz, det M_i, its blend s_i), n = sph.particle_count. Every pass
// that ends a pressure acceleration (D3) applies it once, a^p_i ← L_i a^p_i: L_i is particle i's own,
// so it multiplies the whole sum, fluid and boundary terms alike. CORRECTED reads the pass's PressureAccel.
vec3 corrected_by(vec4 p, vec4 q, vec3 a) {
    return vec3(p.x * a.x + p.w * a.y + q.x * a.z, p.w * a.x + p.y * a.y + q.y * a.z, q.x * a.x + q.y * a.y + p.z * a.z);
}
#ifdef RANRYU_GRADIENT_CORRECTION
#define CORRECTION(i, k) pressure_accel[sph.particle_count + 2u * (i) + (k)]
#define CORRECTED(i, a) corrected_by(CORRECTION(i, 0u), CORRECTION(i, 1u), a)
#else
#define CORRECTED(i, a) (a)
#endif

// (D12), with RANRYU_PRESSURE_STABILISATION: the density solve's residual blends (D6)'s density change
// with the compact Laplacian's, by gamma = dfsph.stabilisation. One pair's weight in that Laplacian,
//     c_ij = −2 (x_ij·∇W_ij)/(|x_ij|² + 0.01h²) ≥ 0,
// so that the compact density change is dt² rho0 Σ_j m (kappa_j − kappa_i) c_ij (boundary particles with
// psi_b and kappa_b: (D9)'s, or 0 with Akinci's term), and its diagonal rho0 Σ_j m c_ij. The accelerate
// and prediction passes sum it beside a^p (Density.y), the residual pass reads it and sums the diagonal.
float compact_weight(vec3 d, vec3 g, float r2) { return -2.0 * dot(d, g) / (r2 + 0.01 * sph.h * sph.h); }
