#pragma once
// The CPU reference of the divergence-free SPH solver (DFSPH; docs/DFSPH.md equations (D1)-(D8)),
// double precision, brute-force neighbour loops, written for reading. The GPU passes of
// glsl/sim/dfsph/ are compared against it. A step, as the GPU runs it:
//
//     f      = factors(x, boundary, psi, p)                        // (D2): 1/D_i, neighbour counts
//     a_nonp = nonpressure_accelerations(x, v, boundary, psi, p)   // (D7): gravity, viscosity (m/ρ0)
//     solve(Solve::divergence, ...)                                // (D5), (D6): v made divergence-free
//     v     += dt·a_nonp
//     solve(Solve::density, ...)                                   // (D4), (D6): ρ* → ρ0
//     x     += dt·v                                                // (D8)
//
// Units are SI; κ_i = p_i/ρ_i² (m⁵ kg⁻¹ s⁻²), so κ does not depend on the time step and a warm
// start carries it from one step to the next unscaled.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "reference/sph_reference.h"

namespace ranryu::reference::dfsph {

struct Settings {
    double boundary_factor = 2.0;      // γ of (D1)-(D3): 2 makes the boundary a mirror of each fluid particle, 1 is Akinci's
    double eta = 1e-4;                 // density solve: mean error bound, in units of ρ0
    double eta_divergence = 1e-3;      // divergence solve: mean of dt·Dρ/Dt bound, in units of ρ0
    int min_iterations = 1, max_iterations = 100;
    int min_divergence_iterations = 1, max_divergence_iterations = 100;
    double relaxation = 0.5;           // ω of (D6)
    double chebyshev = 0.0;            // ρ of (D10), the density solve's Chebyshev acceleration; 0: off
    bool complementarity_error = false;   // (D6): the density solve's error counts |r_i| where κ_i > 0
    double warm_start = 1.0;           // w of (D6): κ⁰ = w·κ of the previous step (density solve)
    double divergence_warm_start = 0.5;   // likewise, the divergence solve
    int deficient_neighbours = 20;     // (D5): fewer neighbours (fluid and boundary, within h) than this: no divergence correction
    double boundary_viscosity = 0.0;   // ν_b of (D7) (m²/s); 0: free-slip walls
    double stabilisation = 0.0;        // γ of (D12): the density solve's blend of the compact Laplacian; 0: off
};

// (D2): the Jacobi diagonal D_i = |A_i + γB_i|² + Σ_j m²|∇W_ij|², with
// A_i = Σ_j m∇W_ij (fluid j ≠ i) and B_i = Σ_b ψ_b∇W_ib; factor_i = 1/D_i, or 0 when D_i vanishes.
struct Factors {
    std::vector<double> factor;
    std::vector<int> neighbours;   // fluid (j ≠ i) and boundary particles within h
};
Factors factors(const std::vector<glm::dvec3>& x, const std::vector<glm::dvec3>& boundary,
                const std::vector<double>& psi, const Params& params, const Settings& s);

// (D3): a_i = −Σ_j m(κ_i + κ_j)∇W_ij − γ·κ_i·Σ_b ψ_b∇W_ib.
std::vector<glm::dvec3> pressure_accelerations(const std::vector<glm::dvec3>& x, const std::vector<double>& kappa,
                                               const std::vector<glm::dvec3>& boundary, const std::vector<double>& psi,
                                               const Params& params, const Settings& s);

// (D11), the kernel-gradient correction: M_i = (1/ρ_i)[Σ_j m (x_j − x_i) ⊗ ∇W_ij + Σ_b ψ_b (x_b − x_i) ⊗ ∇W_ib]
// (ρ_i the summation density of (2)), which is I for every linear field's exact gradient, and
// L_i = s_i M_i⁻¹ + (1 − s_i) I, s_i = clamp((det M_i − 0.4)/(0.7 − 0.4), 0, 1) (RANRYU_CORRECTION_NONE
// and _FULL of shared/bindings.h). The corrected pressure
// acceleration is L_i a_i, a_i of (D3).
struct GradientCorrection {
    glm::dmat3 m{1.0}, l{1.0};
    double det = 1.0, blend = 0.0;
};
std::vector<GradientCorrection> gradient_corrections(const std::vector<glm::dvec3>& x, const std::vector<glm::dvec3>& boundary,
                                                     const std::vector<double>& psi, const std::vector<double>& density,
                                                     const Params& params);
// L_i a_i for each particle.
std::vector<glm::dvec3> corrected(const std::vector<GradientCorrection>& c, const std::vector<glm::dvec3>& a);

// (D1): Dρ_i/Dt = Σ_j m(v_i − v_j)·∇W_ij + γ·Σ_b ψ_b v_i·∇W_ib, the boundary seen as a mirror (γ = 2:
// the image of v_i's normal part approaches as fast as i does) or at rest (γ = 1).
std::vector<double> density_rates(const std::vector<glm::dvec3>& x, const std::vector<glm::dvec3>& v,
                                  const std::vector<glm::dvec3>& boundary, const std::vector<double>& psi,
                                  const Params& params, const Settings& s);

// (D7): g + 2(d+2)ν Σ_j (m/ρ0)(v_ij·x_ij)/(|x_ij|² + 0.01h²)∇W_ij
//         + 2(d+2)ν_b Σ_b (ψ_b/ρ0)(v_i·x_ib)/(|x_ib|² + 0.01h²)∇W_ib.
std::vector<glm::dvec3> nonpressure_accelerations(const std::vector<glm::dvec3>& x, const std::vector<glm::dvec3>& v,
                                                  const std::vector<glm::dvec3>& boundary,
                                                  const std::vector<double>& psi, const Params& params,
                                                  const Settings& s);

enum class Solve { divergence, density };

// (D12): the compact Laplacian's density change per dt², l_i = ρ0 Σ_j m(κ_j − κ_i)c_ij + ρ0 Σ_b ψ_b(0 − κ_i)c_ib
// (the boundary's κ_b = 0: Akinci's term), and its diagonal C_i = ρ0 (Σ_j m c_ij + Σ_b ψ_b c_ib), with
// c_ij = −2(x_ij·∇W_ij)/(|x_ij|² + 0.01h²).
struct Compact {
    std::vector<double> change, diagonal;
};
double compact_weight(const glm::dvec3& d, const CubicKernel& kernel);   // c_ij at d = x_i − x_j
Compact compact_laplacian(const std::vector<glm::dvec3>& x, const std::vector<double>& kappa, const std::vector<glm::dvec3>& boundary,
                          const std::vector<double>& psi, const Params& params);
// The same with the rows' κ_b of (D9) or (D13) per boundary particle: ρ0 Σ_b ψ_b (κ_b − κ_i) c_ib.
Compact compact_laplacian(const std::vector<glm::dvec3>& x, const std::vector<double>& kappa, const std::vector<glm::dvec3>& boundary,
                          const std::vector<double>& psi, const std::vector<double>& kappa_b, const Params& params);

// One solve of (D4)/(D5) with the Jacobi iteration of (D6), starting from kappa (the warm start,
// updated in place; the first iteration drops it where the particle separates: deficient, or its
// predicted change leaves it more than 1 % of ρ0 below ρ0). Velocities get the final pressure
// accelerations: v += dt·a(κ).
struct SolveResult {
    int iterations = 0;
    double error = 0.0;             // the last iteration's mean error, in units of ρ0
    std::vector<double> source;     // s_i of (D4)/(D5)
};
SolveResult solve(Solve which, const std::vector<glm::dvec3>& x, std::vector<glm::dvec3>& v,
                  const std::vector<double>& density, const Factors& f, std::vector<double>& kappa,
                  const std::vector<glm::dvec3>& boundary, const std::vector<double>& psi, const Params& params,
                  const Settings& s, double dt);

// (D9), the boundary rows: a boundary particle b within h of some fluid particle is a row with its own
// kappa_b; the fluid pairs with it as with a fluid neighbour, a_i −= psi_b (κ_i + κ_b) ∇W_ib. These
// functions take kappa_b per boundary particle (0 where b is no row).
//
// u_i = |Σ_j m∇W_ij + Σ_b ψ_b∇W_ib| + Σ_j m|∇W_ij| + Σ_b m|∇W_ib|: the bound on how much one unit of
// multiplier at any row moves particle i, which the rows' l1 diagonal sums.
std::vector<double> spreads(const std::vector<glm::dvec3>& x, const std::vector<glm::dvec3>& boundary,
                            const std::vector<double>& psi, const Params& params);
// Whether each boundary particle is a row: some fluid particle within h.
std::vector<bool> boundary_rows(const std::vector<glm::dvec3>& x, const std::vector<glm::dvec3>& boundary, const Params& params);
// A solve's rows: s_b = max(ρ0, Σ_b' ψ_b' W_bb') − ρ*_b (density; ρ*_b = Σ_j m W_bj + Σ_b' ψ_b' W_bb' + dt Σ_j m(0 − v_j)·∇W_bj)
// or −dt Σ_j m(0 − v_j)·∇W_bj (divergence); D_b = ψ_b Σ_j |∇W_bj| u_j. 0 for both where b is no row.
struct Rows {
    std::vector<double> source, diagonal;
};
Rows row_sources(Solve which, const std::vector<glm::dvec3>& x, const std::vector<glm::dvec3>& v, const std::vector<double>& u,
                 const std::vector<glm::dvec3>& boundary, const std::vector<double>& psi, const Params& params, double dt);
// One l1-Jacobi update of the rows from the fluid's pressure accelerations a:
// κ_b ← max(κ_b + ω_b r_b / (dt² D_b), 0), r_b = dt² Σ_j m(0 − a_j)·∇W_bj − s_b.
void correct_rows(const std::vector<glm::dvec3>& x, const std::vector<glm::dvec3>& a, const Rows& rows,
                  const std::vector<glm::dvec3>& boundary, const Params& params, double omega_b, double dt,
                  std::vector<double>& kappa_b);
// (D13), the density solve's rows eliminated: κ_b = max(Σ_j W_bj (κ_j + [κ_j > 0] g·(x_b − x_j)/ρ0) / Σ_j W_bj, 0),
// the fluid's κ extended to each row with the hydrostatic offset from fluid that carries pressure; 0 where b is no row.
std::vector<double> extended_pressure(const std::vector<glm::dvec3>& x, const std::vector<double>& kappa,
                                      const std::vector<glm::dvec3>& boundary, const Params& params);
// (D13): each row's excess handed on, q_b = (ψ_b/m) max(r_b, 0) / Σ_j W_bj with (D9)'s r_b = dt² Σ_j m(0 − a_j)·∇W_bj − s_b
// (rows.source), 0 where b is no row; and what particle i takes of them, Σ_b W_ib q_b, added to its residual.
std::vector<double> handed_excess(const std::vector<glm::dvec3>& x, const std::vector<glm::dvec3>& a, const Rows& rows,
                                  const std::vector<glm::dvec3>& boundary, const std::vector<double>& psi, const Params& params, double dt);
std::vector<double> handed_to_fluid(const std::vector<glm::dvec3>& x, const std::vector<glm::dvec3>& boundary,
                                    const std::vector<double>& q, const Params& params);
// (D13)'s Jacobi diagonal, D_i = |A_i + B_i|·|A_i + 2B_i| + Σ_j m²|∇W_ij|² (A_i, B_i of (D2)): a particle alone at a
// wall moves the rows it sees with it (κ_b = κ_i).
std::vector<double> eliminated_factors(const std::vector<glm::dvec3>& x, const std::vector<glm::dvec3>& boundary,
                                       const std::vector<double>& psi, const Params& params);

// (D3) with (D9): a_i = −Σ_j m(κ_i + κ_j)∇W_ij − Σ_b ψ_b(κ_i + κ_b)∇W_ib (boundary_factor 1).
std::vector<glm::dvec3> pressure_accelerations(const std::vector<glm::dvec3>& x, const std::vector<double>& kappa,
                                               const std::vector<glm::dvec3>& boundary, const std::vector<double>& psi,
                                               const std::vector<double>& kappa_b, const Params& params);

// The fluid between steps: positions, velocities and the two warm-start stiffnesses κ (density
// solve) and κ_v (divergence solve) of the last step.
struct State {
    std::vector<glm::dvec3> x, v;
    std::vector<double> kappa, kappa_v;
};

struct StepResult {
    std::vector<double> density;          // ρ_i at the start of the step, (2)
    std::vector<double> pressure;         // (κ_i + κ_v,i)·ρ_i², the step's pressure
    SolveResult divergence, density_solve;
};
// One whole step of dt (the step of the header comment); the warm starts are w·κ of the last step.
StepResult step(State& state, const std::vector<glm::dvec3>& boundary, const std::vector<double>& psi,
                const Params& params, const Settings& s, double dt, bool divergence_solve = true);

// (D8): the CFL step 0.4·Δx/v_max, the force condition 0.25·√(Δx/a_max), at most dt_max.
double time_step(const Params& params, double v_max, double a_max, double dt_max);

}  // namespace ranryu::reference::dfsph
