#pragma once
// The CPU reference of Position Based Fluids (docs/PBF.md equations (P1)-(P9)), double precision,
// brute-force neighbour loops, written for reading. The GPU passes of glsl/sim/pbf/ are compared
// against it. A step, as the GPU runs it:
//
//     x* = x + dt (v + dt g)                                   // (P1)
//     N  = neighbours(x*, h)                                   // the fluid neighbours, fixed for the step
//     iterations × { lambda = lambdas(x*, N, ...)              // (P2)-(P4)
//                    x*    += corrections(x*, lambda, N, ...)  // (P5), (P6) }
//     v  = (x* − x) / dt                                       // (P7)
//     ω  = vorticities(x*, v, N, ...)                          // (P8), of these velocities
//     v  = xsph(x*, v, N, ...)                                 // (P7)
//     v  = confine_vorticity(x*, v, ω, ...)                    // (P8), when epsilon_v > 0
//
// Units are SI. The fluid neighbours of every pass are the sets N found on the predicted positions
// (i included), evaluated at the current positions (W and ∇W vanish beyond h); the boundary
// particles are every one, evaluated at the current positions.
#include <cstdint>
#include <functional>
#include <vector>

#include <glm/glm.hpp>

#include "reference/sph_reference.h"

namespace ranryu::reference::pbf {

using Neighbours = std::vector<std::vector<std::uint32_t>>;   // per particle, i included (reference::neighbours)

struct Settings {
    double epsilon = 0.0;        // epsilon of (P4) (1/m²)
    double s_corr_scale = 0.0;   // k·Δx² of (P5) (m²)
    double s_corr_n = 4.0;       // n of (P5)
    double w_dq = 1.0;           // W(|Δq|) of (P5)
    double xsph = 0.0;           // c of (P7)
    double vorticity = 0.0;      // epsilon of (P8) (m/s)
    // The scene keys of docs/PBF.md: relaxation in 1/Δx², |Δq| in h.
    static Settings from_keys(const Params& p, double relaxation, double k, double n, double dq, double xsph, double vorticity);
};

// (P2)-(P4): ρ_i, λ_i and Σ|∇C|² of every particle.
struct Lambdas {
    std::vector<double> density, lambda, gradient_squares;
};
Lambdas lambdas(const std::vector<glm::dvec3>& x, const Neighbours& n, const std::vector<glm::dvec3>& boundary,
                const std::vector<double>& psi, const Params& p, const Settings& s);

// (P5), (P6): Δx_i.
std::vector<glm::dvec3> corrections(const std::vector<glm::dvec3>& x, const std::vector<double>& lambda, const Neighbours& n,
                                    const std::vector<glm::dvec3>& boundary, const std::vector<double>& psi, const Params& p,
                                    const Settings& s);

// (P7): v_i + c Σ_j (m/ρ_j)(v_j − v_i) W_ij, ρ_j the densities given.
std::vector<glm::dvec3> xsph(const std::vector<glm::dvec3>& x, const std::vector<glm::dvec3>& v, const std::vector<double>& density,
                             const Neighbours& n, const Params& p, const Settings& s);

// (P8): ω_i = Σ_j (m/ρ_j) ∇W_ij × (v_j − v_i).
std::vector<glm::dvec3> vorticities(const std::vector<glm::dvec3>& x, const std::vector<glm::dvec3>& v,
                                    const std::vector<double>& density, const Neighbours& n, const Params& p);
// (P8): v_i + dt ε (N_i × ω_i), N_i = η_i/|η_i|, η_i = Σ_j (m/ρ_j)(|ω_j| − |ω_i|)∇W_ij.
std::vector<glm::dvec3> confine_vorticity(const std::vector<glm::dvec3>& x, const std::vector<glm::dvec3>& v,
                                          const std::vector<glm::dvec3>& omega, const std::vector<double>& density,
                                          const Neighbours& n, const Params& p, const Settings& s, double dt);

struct State {
    std::vector<glm::dvec3> x, v;
};
struct StepResult {
    std::vector<double> density;    // ρ_i of the last λ pass
    std::vector<double> pressure;   // (P9): −(ρ0/dt²) Σ λ_i over the iterations
};
// The fluid neighbours of the passes after the first λ pass, given their positions and the sets N
// found on x*: N itself by default (Macklin & Müller's scheme); the GPU's particles without complete
// neighbour masks find theirs again at each pass's positions, which a test replicates with this.
using Regather = std::function<Neighbours(const std::vector<glm::dvec3>& x, const Neighbours& fixed)>;

// One whole step (the header's), without the last-resort projection.
StepResult step(State& state, const std::vector<glm::dvec3>& boundary, const std::vector<double>& psi, const Params& p,
                const Settings& s, double dt, int iterations, const Regather& regather = {});

}  // namespace ranryu::reference::pbf
