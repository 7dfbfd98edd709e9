#include "reference/sph_reference.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace ranryu::reference {

using glm::dvec3;

// ---- eq. (1): cubic spline ----------------------------------------------------------------------------

double CubicKernel::W(double r) const {
    const double k = 8.0 / (std::numbers::pi * h * h * h);
    const double q = r / h;
    if (q <= 0.5) return k * (6.0 * q * q * q - 6.0 * q * q + 1.0);
    if (q <= 1.0) return k * 2.0 * (1.0 - q) * (1.0 - q) * (1.0 - q);
    return 0.0;
}

dvec3 CubicKernel::gradW(const dvec3& r) const {
    const double l = 48.0 / (std::numbers::pi * h * h * h);
    const double len = glm::length(r);
    const double q = len / h;
    // q·r̂/h = r/h², so the inner branch needs no r̂ and is exactly 0 at r = 0.
    if (q <= 0.5) return l * (3.0 * q - 2.0) * r / (h * h);
    if (q <= 1.0) return -l * (1.0 - q) * (1.0 - q) * (r / len) / h;
    return dvec3(0.0);
}

// ---- parameters ---------------------------------------------------------------------------------------

Params Params::from_spacing(double spacing, double rest_density, double speed_of_sound, double viscosity,
                            dvec3 gravity) {
    return Params{spacing,        2.0 * spacing, rest_density, rest_density * spacing * spacing * spacing,
                  speed_of_sound, viscosity,     gravity};
}

double Params::B() const { return rest_density * speed_of_sound * speed_of_sound / 7.0; }

// ---- eq. (2): boundary volumes (Akinci et al. 2012, eqs. 4–5) -------------------------------------------

std::vector<double> boundary_volumes(const std::vector<dvec3>& boundary, const CubicKernel& kernel) {
    std::vector<double> volume(boundary.size());
    for (size_t b = 0; b < boundary.size(); ++b) {
        double number_density = 0.0;
        for (const dvec3& xb2 : boundary) number_density += kernel.W(glm::length(boundary[b] - xb2));
        volume[b] = 1.0 / number_density;
    }
    return volume;
}

std::vector<double> boundary_psi(const std::vector<dvec3>& boundary, const Params& params) {
    std::vector<double> psi = boundary_volumes(boundary, CubicKernel{params.h});
    const double cell = params.spacing * params.spacing * params.spacing;
    for (double& p : psi) p = params.rest_density * std::min(p, cell);   // eq. (2): V_b capped at Δx³
    return psi;
}

// ---- eq. (2): density ---------------------------------------------------------------------------------

std::vector<double> densities(const std::vector<dvec3>& x, const std::vector<dvec3>& boundary,
                              const std::vector<double>& psi, const Params& params) {
    const CubicKernel kernel{params.h};
    std::vector<double> density(x.size());
    for (size_t i = 0; i < x.size(); ++i) {
        double rho = 0.0;
        for (const dvec3& xj : x) rho += params.mass * kernel.W(glm::length(x[i] - xj));
        for (size_t b = 0; b < boundary.size(); ++b) rho += psi[b] * kernel.W(glm::length(x[i] - boundary[b]));
        density[i] = rho;
    }
    return density;
}

// ---- eq. (3): Tait equation of state, clamped at zero ---------------------------------------------------

double tait_pressure(double density, const Params& params) {
    return std::max(0.0, params.B() * (std::pow(density / params.rest_density, 7) - 1.0));
}

std::vector<double> pressures(const std::vector<double>& density, const Params& params) {
    std::vector<double> pressure(density.size());
    for (size_t i = 0; i < density.size(); ++i) pressure[i] = tait_pressure(density[i], params);
    return pressure;
}

// ---- eq. (4): symmetric pressure acceleration, Akinci boundary term ------------------------------------

std::vector<dvec3> pressure_accelerations(const std::vector<dvec3>& x, const std::vector<double>& density,
                                          const std::vector<double>& pressure, const std::vector<dvec3>& boundary,
                                          const std::vector<double>& psi, const Params& params) {
    const CubicKernel kernel{params.h};
    std::vector<dvec3> accel(x.size());
    for (size_t i = 0; i < x.size(); ++i) {
        const double pi_over_rho2 = pressure[i] / (density[i] * density[i]);
        dvec3 a(0.0);
        for (size_t j = 0; j < x.size(); ++j) {
            const double pj_over_rho2 = pressure[j] / (density[j] * density[j]);
            a -= params.mass * (pi_over_rho2 + pj_over_rho2) * kernel.gradW(x[i] - x[j]);
        }
        // Akinci et al. 2012, eq. 10: the boundary mirrors p_i and ρ_i.
        for (size_t b = 0; b < boundary.size(); ++b) a -= psi[b] * pi_over_rho2 * kernel.gradW(x[i] - boundary[b]);
        accel[i] = a;
    }
    return accel;
}

// ---- eq. (5): viscosity (Monaghan 2005; Morris et al. 1997), and eq. (5a): α·c·Δx on approaching pairs ----

std::vector<dvec3> viscosity_accelerations(const std::vector<dvec3>& x, const std::vector<dvec3>& v,
                                           const std::vector<double>& density, const Params& params) {
    const CubicKernel kernel{params.h};
    const double d = 3.0;
    const double eta = 0.01 * params.h * params.h;
    std::vector<dvec3> accel(x.size());
    for (size_t i = 0; i < x.size(); ++i) {
        dvec3 sum(0.0), approaching(0.0);
        for (size_t j = 0; j < x.size(); ++j) {
            const dvec3 xij = x[i] - x[j];
            const dvec3 vij = v[i] - v[j];
            const dvec3 term = (2.0 * params.mass / (density[i] + density[j])) * glm::dot(vij, xij) /
                               (glm::dot(xij, xij) + eta) * kernel.gradW(xij);
            sum += term;
            if (glm::dot(vij, xij) < 0.0) approaching += term;
        }
        accel[i] = 2.0 * (d + 2.0) * params.viscosity * sum +
                   params.artificial_viscosity * params.speed_of_sound * params.spacing * approaching;
    }
    return accel;
}

// ---- all fields ---------------------------------------------------------------------------------------

Fields compute_fields(const State& fluid, const std::vector<dvec3>& boundary, const std::vector<double>& psi,
                      const Params& params) {
    Fields f;
    f.density = densities(fluid.x, boundary, psi, params);                                              // (2)
    f.pressure = pressures(f.density, params);                                                          // (3)
    f.accel_pressure = pressure_accelerations(fluid.x, f.density, f.pressure, boundary, psi, params);   // (4)
    f.accel_viscosity = viscosity_accelerations(fluid.x, fluid.v, f.density, params);                   // (5)
    f.accel.resize(fluid.x.size());
    for (size_t i = 0; i < fluid.x.size(); ++i)
        f.accel[i] = f.accel_pressure[i] + f.accel_viscosity[i] + params.gravity;  // the sum of eq. (6)
    return f;
}

// ---- eq. (6): symplectic Euler ------------------------------------------------------------------------

void step(State& state, const Fields& fields, double dt) {
    for (size_t i = 0; i < state.x.size(); ++i) {
        state.v[i] += dt * fields.accel[i];
        state.x[i] += dt * state.v[i];
    }
}

// ---- eq. (7): time step -------------------------------------------------------------------------------

double cfl_dt(const Params& params, double v_max, double a_max, double dt_frame_remaining) {
    double dt = std::min(0.4 * params.spacing / (params.speed_of_sound + v_max), dt_frame_remaining);
    if (a_max > 0.0) dt = std::min(dt, 0.25 * std::sqrt(params.spacing / a_max));
    return dt;
}

double max_norm(const std::vector<dvec3>& a) {
    double m = 0.0;
    for (const dvec3& ai : a) m = std::max(m, glm::length(ai));
    return m;
}

// ---- neighbour sets -----------------------------------------------------------------------------------

std::vector<std::vector<uint32_t>> neighbours(const std::vector<dvec3>& x, double h) {
    std::vector<std::vector<uint32_t>> result(x.size());
    for (size_t i = 0; i < x.size(); ++i)
        for (size_t j = 0; j < x.size(); ++j)
            if (glm::length(x[i] - x[j]) < h) result[i].push_back(static_cast<uint32_t>(j));
    return result;
}

// ---- lattices -----------------------------------------------------------------------------------------

std::vector<dvec3> lattice(dvec3 min, glm::ivec3 n, double spacing) {
    std::vector<dvec3> points;
    points.reserve(size_t(std::max(n.x, 0)) * size_t(std::max(n.y, 0)) * size_t(std::max(n.z, 0)));
    for (int k = 0; k < n.z; ++k)
        for (int j = 0; j < n.y; ++j)
            for (int i = 0; i < n.x; ++i) points.push_back(min + (dvec3(i, j, k) + 0.5) * spacing);
    return points;
}

std::vector<dvec3> box_boundary(dvec3 min, dvec3 max, double spacing, int layers) {
    glm::ivec3 n;  // fluid cells per axis
    for (int a = 0; a < 3; ++a) {
        const double cells = (max[a] - min[a]) / spacing;
        n[a] = static_cast<int>(std::lround(cells));
        if (n[a] < 1 || std::abs(cells - n[a]) > 1e-6)
            throw std::invalid_argument("box_boundary: each extent must be a whole multiple of the spacing");
    }
    std::vector<dvec3> points;
    for (int k = -layers; k < n.z + layers; ++k)
        for (int j = -layers; j < n.y + layers; ++j)
            for (int i = -layers; i < n.x + layers; ++i) {
                const bool inside = 0 <= i && i < n.x && 0 <= j && j < n.y && 0 <= k && k < n.z;
                if (!inside) points.push_back(min + (dvec3(i, j, k) + 0.5) * spacing);
            }
    return points;
}

}  // namespace ranryu::reference
