#pragma once
// The CPU reference SPH: docs/SPH.md equations (1)–(8) in double precision, written for reading, not
// speed (brute-force O(n·(n+m)) neighbour loops, no grid). The GPU passes of glsl/sim/ are compared
// against it. A step is a handful of named calls on flat arrays, as in Ten Minute Physics:
//
//     psi    = boundary_psi(boundary, params)                  // eq. (2), once per boundary
//     fields = compute_fields(state, boundary, psi, params)    // eqs. (2)(3)(4)(5) + gravity
//     dt     = cfl_dt(params, max_norm(state.v), max_norm(fields.accel), dt_frame_remaining)  // eq. (7)
//     step(state, fields, dt)                                  // eq. (6)
//
// Units are SI. Fluid particle i, fluid neighbour j, boundary particle b; x_ij = x_i − x_j.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace ranryu::reference {

// eq. (1): the cubic spline of Monaghan 1992 with support radius h (W = 0 for r ≥ h), normalised in 3-D.
// The same form as SPlisHSPlasH's CubicKernel.
struct CubicKernel {
    double h;

    // W(r) for r = |x_i − x_j| ≥ 0.
    double W(double r) const;
    // ∇W at r = x_i − x_j, the gradient with respect to x_i. ∇W(0) = 0 and ∇W(−r) = −∇W(r) exactly.
    glm::dvec3 gradW(const glm::dvec3& r) const;
};

// The constants of a simulation (docs/SPH.md "Symbols").
struct Params {
    double spacing;         // Δx (m)
    double h;               // kernel support radius (m), 2·Δx
    double rest_density;    // ρ0 (kg/m³)
    double mass;            // m = ρ0·Δx³ (kg)
    double speed_of_sound;  // c (m/s)
    double viscosity;       // ν, kinematic (m²/s)
    glm::dvec3 gravity;     // g (m/s²)
    double artificial_viscosity = 0.0;   // α of eq. (5a) (WCSPH), on approaching pairs; 0: none

    // Derives h = 2·Δx and m = ρ0·Δx³ from the spacing.
    static Params from_spacing(double spacing, double rest_density, double speed_of_sound, double viscosity,
                               glm::dvec3 gravity);
    // eq. (3): the Tait stiffness B = ρ0·c²/7 (Pa).
    double B() const;
};

// eq. (2): V_b = 1 / Σ_b′ W(x_b − x_b′) over all boundary particles b′, b itself included
// (Akinci et al. 2012, eq. 4).
std::vector<double> boundary_volumes(const std::vector<glm::dvec3>& boundary, const CubicKernel& kernel);
// eq. (2): ψ_b = ρ0·V_b (Akinci et al. 2012, eq. 5).
std::vector<double> boundary_psi(const std::vector<glm::dvec3>& boundary, const Params& params);

struct State {
    std::vector<glm::dvec3> x, v;
};

// Everything compute_fields derives from a State, one entry per fluid particle.
struct Fields {
    std::vector<double> density;              // ρ_i, eq. (2)
    std::vector<double> pressure;             // p_i, eq. (3)
    std::vector<glm::dvec3> accel_pressure;   // a_i^p, eq. (4)
    std::vector<glm::dvec3> accel_viscosity;  // a_i^ν, eq. (5)
    std::vector<glm::dvec3> accel;            // a_i^p + a_i^ν + g, what eq. (6) integrates
};

// The phases of compute_fields, exposed so tests can feed them chosen densities and pressures.
// eq. (2): ρ_i = Σ_j m·W(x_ij) + Σ_b ψ_b·W(x_i − x_b), j over all fluid particles including i.
std::vector<double> densities(const std::vector<glm::dvec3>& x, const std::vector<glm::dvec3>& boundary,
                              const std::vector<double>& psi, const Params& params);
// eq. (3): p = max(0, B·((ρ/ρ0)^7 − 1)).
double tait_pressure(double density, const Params& params);
std::vector<double> pressures(const std::vector<double>& density, const Params& params);
// eq. (4): a_i^p = −Σ_j m·(p_i/ρ_i² + p_j/ρ_j²)·∇W(x_ij) − Σ_b ψ_b·(p_i/ρ_i²)·∇W(x_i − x_b).
std::vector<glm::dvec3> pressure_accelerations(const std::vector<glm::dvec3>& x, const std::vector<double>& density,
                                               const std::vector<double>& pressure,
                                               const std::vector<glm::dvec3>& boundary,
                                               const std::vector<double>& psi, const Params& params);
// eq. (5): a_i^ν = 2·(d+2)·ν·Σ_j (2m/(ρ_i+ρ_j))·(v_ij·x_ij)/(|x_ij|² + 0.01·h²)·∇W(x_ij), d = 3, fluid–fluid only.
std::vector<glm::dvec3> viscosity_accelerations(const std::vector<glm::dvec3>& x, const std::vector<glm::dvec3>& v,
                                                const std::vector<double>& density, const Params& params);

// eqs. (2)(3)(4)(5) and gravity for every fluid particle; psi from boundary_psi (one entry per boundary
// particle; both may be empty).
Fields compute_fields(const State& fluid, const std::vector<glm::dvec3>& boundary, const std::vector<double>& psi,
                      const Params& params);

// eq. (6), symplectic Euler: v_i ← v_i + Δt·a_i, then x_i ← x_i + Δt·v_i (the new v_i).
void step(State& state, const Fields& fields, double dt);

// eq. (7): Δt = min(0.4·Δx/(c + v_max), 0.25·√(Δx/a_max), dt_frame_remaining), where v_max and a_max are
// the largest |v_i| and |a_i| (a_i the total acceleration, Fields::accel). a_max = 0 drops the force term.
double cfl_dt(const Params& params, double v_max, double a_max, double dt_frame_remaining);
// max_i |a_i| (0 for an empty array): v_max and a_max for cfl_dt.
double max_norm(const std::vector<glm::dvec3>& a);

// For each i, every j (i included) with |x_i − x_j| < h, ascending: the sets the GPU grid must find.
std::vector<std::vector<uint32_t>> neighbours(const std::vector<glm::dvec3>& x, double h);

// The n.x·n.y·n.z centres of the cubic cells of side `spacing` filling [min, min + n·spacing]:
// min + (i + ½)·spacing, the scene's block convention; x fastest, then y, then z.
std::vector<glm::dvec3> lattice(glm::dvec3 min, glm::ivec3 n, double spacing);

// eq. (8): boundary particles on the same cell-centred lattice as lattice(min, …, spacing), filling
// `layers` layers outside every face of the box [min, max], edges and corners included, so the shell is
// closed: lattice(min, n, Δx) and box_boundary(min, min + n·Δx, Δx, L) together form one uniform lattice.
// Each extent max − min must be a whole multiple of spacing (std::invalid_argument otherwise).
std::vector<glm::dvec3> box_boundary(glm::dvec3 min, glm::dvec3 max, double spacing, int layers);

}  // namespace ranryu::reference
