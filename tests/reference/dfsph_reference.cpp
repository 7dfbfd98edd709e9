#include "reference/dfsph_reference.h"

#include <algorithm>
#include <cmath>

#include "shared/bindings.h"

namespace ranryu::reference::dfsph {

using glm::dvec3;

Factors factors(const std::vector<dvec3>& x, const std::vector<dvec3>& boundary, const std::vector<double>& psi,
                const Params& params, const Settings& s) {
    const CubicKernel kernel{params.h};
    Factors f;
    f.factor.resize(x.size());
    f.neighbours.resize(x.size());
    for (size_t i = 0; i < x.size(); ++i) {
        dvec3 fluid(0.0), wall(0.0);
        double squares = 0.0;
        int count = 0;
        for (size_t j = 0; j < x.size(); ++j) {
            if (j == i || glm::length(x[i] - x[j]) >= params.h) continue;
            const dvec3 g = params.mass * kernel.gradW(x[i] - x[j]);
            fluid += g;
            squares += glm::dot(g, g);
            ++count;
        }
        for (size_t b = 0; b < boundary.size(); ++b) {
            if (glm::length(x[i] - boundary[b]) >= params.h) continue;
            wall += psi[b] * kernel.gradW(x[i] - boundary[b]);
            ++count;
        }
        const dvec3 sum = fluid + s.boundary_factor * wall;
        const double d = glm::dot(sum, sum) + squares;
        f.factor[i] = d > 0.0 ? 1.0 / d : 0.0;
        f.neighbours[i] = count;
    }
    return f;
}

std::vector<dvec3> pressure_accelerations(const std::vector<dvec3>& x, const std::vector<double>& kappa,
                                          const std::vector<dvec3>& boundary, const std::vector<double>& psi,
                                          const Params& params, const Settings& s) {
    const CubicKernel kernel{params.h};
    std::vector<dvec3> a(x.size(), dvec3(0.0));
    for (size_t i = 0; i < x.size(); ++i) {
        for (size_t j = 0; j < x.size(); ++j) a[i] -= params.mass * (kappa[i] + kappa[j]) * kernel.gradW(x[i] - x[j]);
        for (size_t b = 0; b < boundary.size(); ++b)
            a[i] -= s.boundary_factor * kappa[i] * psi[b] * kernel.gradW(x[i] - boundary[b]);
    }
    return a;
}

std::vector<GradientCorrection> gradient_corrections(const std::vector<dvec3>& x, const std::vector<dvec3>& boundary,
                                                     const std::vector<double>& psi, const std::vector<double>& density,
                                                     const Params& params) {
    const CubicKernel kernel{params.h};
    constexpr double none = RANRYU_CORRECTION_NONE, full = RANRYU_CORRECTION_FULL;   // as the density pass
    std::vector<GradientCorrection> out(x.size());
    for (size_t i = 0; i < x.size(); ++i) {
        glm::dmat3 m(0.0);
        for (size_t j = 0; j < x.size(); ++j) m += params.mass * glm::outerProduct(kernel.gradW(x[i] - x[j]), x[j] - x[i]);
        for (size_t b = 0; b < boundary.size(); ++b)
            m += psi[b] * glm::outerProduct(kernel.gradW(x[i] - boundary[b]), boundary[b] - x[i]);
        GradientCorrection& c = out[i];
        c.m = m / density[i];
        c.det = glm::determinant(c.m);
        c.blend = std::clamp((c.det - none) / (full - none), 0.0, 1.0);
        c.l = c.blend > 0.0 ? c.blend * glm::inverse(c.m) + (1.0 - c.blend) * glm::dmat3(1.0) : glm::dmat3(1.0);
    }
    return out;
}

std::vector<dvec3> corrected(const std::vector<GradientCorrection>& c, const std::vector<dvec3>& a) {
    std::vector<dvec3> out(a.size());
    for (size_t i = 0; i < a.size(); ++i) out[i] = c[i].l * a[i];
    return out;
}

std::vector<double> density_rates(const std::vector<dvec3>& x, const std::vector<dvec3>& v,
                                  const std::vector<dvec3>& boundary, const std::vector<double>& psi,
                                  const Params& params, const Settings& s) {
    const CubicKernel kernel{params.h};
    std::vector<double> rate(x.size(), 0.0);
    for (size_t i = 0; i < x.size(); ++i) {
        for (size_t j = 0; j < x.size(); ++j) rate[i] += params.mass * glm::dot(v[i] - v[j], kernel.gradW(x[i] - x[j]));
        for (size_t b = 0; b < boundary.size(); ++b)
            rate[i] += s.boundary_factor * psi[b] * glm::dot(v[i], kernel.gradW(x[i] - boundary[b]));
    }
    return rate;
}

std::vector<dvec3> nonpressure_accelerations(const std::vector<dvec3>& x, const std::vector<dvec3>& v,
                                             const std::vector<dvec3>& boundary, const std::vector<double>& psi,
                                             const Params& params, const Settings& s) {
    const CubicKernel kernel{params.h};
    const double eps = 0.01 * params.h * params.h, d = 3.0, volume = params.mass / params.rest_density;
    std::vector<dvec3> a(x.size(), params.gravity);
    for (size_t i = 0; i < x.size(); ++i) {
        dvec3 fluid(0.0), wall(0.0);
        for (size_t j = 0; j < x.size(); ++j) {
            const dvec3 xij = x[i] - x[j];
            fluid += volume * glm::dot(v[i] - v[j], xij) / (glm::dot(xij, xij) + eps) * kernel.gradW(xij);
        }
        for (size_t b = 0; b < boundary.size(); ++b) {
            const dvec3 xib = x[i] - boundary[b];
            wall += (psi[b] / params.rest_density) * glm::dot(v[i], xib) / (glm::dot(xib, xib) + eps) * kernel.gradW(xib);
        }
        a[i] += 2.0 * (d + 2.0) * (params.viscosity * fluid + s.boundary_viscosity * wall);
    }
    return a;
}

SolveResult solve(Solve which, const std::vector<dvec3>& x, std::vector<dvec3>& v, const std::vector<double>& density,
                  const Factors& f, std::vector<double>& kappa, const std::vector<dvec3>& boundary,
                  const std::vector<double>& psi, const Params& params, const Settings& s, double dt) {
    const CubicKernel kernel{params.h};
    const double rho0 = params.rest_density;
    const size_t n = x.size();
    SolveResult r;
    // (D4), (D5): the density change that would bring i to ρ0 (to a steady density); with κ ≥ 0 the
    // solve only ever removes an excess (D6).
    const std::vector<double> rate = density_rates(x, v, boundary, psi, params, s);
    r.source.resize(n);
    std::vector<bool> drop(n);   // the warm start is dropped where the particle separates (D6)
    for (size_t i = 0; i < n; ++i) {
        // s_i = ρ0 − ρ*_i (density) or −Δt·Dρ/Dt (divergence); ρ0 where i is deficient (no correction).
        const bool deficient = which == Solve::divergence && f.neighbours[i] < s.deficient_neighbours;
        const double change = which == Solve::density ? rho0 - (density[i] + dt * rate[i]) : -dt * rate[i];
        r.source[i] = deficient ? rho0 : change;
        drop[i] = deficient || change > 0.01 * rho0;
    }
    const int lo = which == Solve::density ? s.min_iterations : s.min_divergence_iterations;
    const int hi = which == Solve::density ? s.max_iterations : s.max_divergence_iterations;
    const double eta = which == Solve::density ? s.eta : s.eta_divergence;
    // (D6): relaxed Jacobi on κ ≥ 0; the error is the residual of the κ the iteration started from.
    // (D10): the density solve's iteration k ≥ 2 takes κ ← max(w_k (J − κ^(k−1)) + κ^(k−1), 0).
    const bool chebyshev = which == Solve::density && s.chebyshev > 0.0;
    std::vector<double> previous(n, 0.0);
    double weight = 1.0;
    while (r.iterations < hi) {
        const double rho2 = s.chebyshev * s.chebyshev;
        if (r.iterations == 2) weight = 2.0 / (2.0 - rho2);
        else if (r.iterations > 2) weight = 4.0 / (4.0 - rho2 * weight);
        const std::vector<dvec3> a = pressure_accelerations(x, kappa, boundary, psi, params, s);
        // (D12): the density solve blends in the compact Laplacian's change and diagonal by γ.
        const double gamma = which == Solve::density ? s.stabilisation : 0.0;
        const Compact compact = gamma > 0.0 ? compact_laplacian(x, kappa, boundary, psi, params) : Compact{};
        double error = 0.0;
        for (size_t i = 0; i < n; ++i) {
            double change = 0.0;   // δρ_i = dt²[Σ_j m(a_i − a_j)·∇W_ij + γΣ_b ψ_b a_i·∇W_ib]
            for (size_t j = 0; j < n; ++j) change += params.mass * glm::dot(a[i] - a[j], kernel.gradW(x[i] - x[j]));
            for (size_t b = 0; b < boundary.size(); ++b)
                change += s.boundary_factor * psi[b] * glm::dot(a[i], kernel.gradW(x[i] - boundary[b]));
            double factor = f.factor[i];
            if (gamma > 0.0) {
                change = (1.0 - gamma) * change + gamma * compact.change[i];
                const double blended = (1.0 - gamma) / f.factor[i] + gamma * compact.diagonal[i];
                factor = f.factor[i] > 0.0 && blended > 0.0 ? 1.0 / blended : 0.0;
            }
            change *= dt * dt;
            const double residual = change - r.source[i];
            const double start = r.iterations == 0 && drop[i] ? 0.0 : kappa[i];
            double next = std::max(start + s.relaxation * residual * factor / (dt * dt), 0.0);
            if (chebyshev && r.iterations >= 2) next = std::max(weight * (next - previous[i]) + previous[i], 0.0);
            previous[i] = start;
            kappa[i] = next;
            // (D6): the excess, or with the complementarity error |r_i| where i carries pressure.
            const bool held = which == Solve::density && s.complementarity_error && start > 0.0;
            error += std::min((held ? std::abs(residual) : std::max(residual, 0.0)) / rho0, 1.0);
        }
        ++r.iterations;
        r.error = n ? error / double(n) : 0.0;
        if (r.iterations >= lo && r.error <= eta) break;
    }
    const std::vector<dvec3> a = pressure_accelerations(x, kappa, boundary, psi, params, s);
    for (size_t i = 0; i < n; ++i) v[i] += dt * a[i];
    return r;
}

double compact_weight(const dvec3& d, const CubicKernel& kernel) {
    return -2.0 * glm::dot(d, kernel.gradW(d)) / (glm::dot(d, d) + 0.01 * kernel.h * kernel.h);
}

Compact compact_laplacian(const std::vector<dvec3>& x, const std::vector<double>& kappa, const std::vector<dvec3>& boundary,
                          const std::vector<double>& psi, const Params& params) {
    return compact_laplacian(x, kappa, boundary, psi, std::vector<double>(boundary.size(), 0.0), params);
}

Compact compact_laplacian(const std::vector<dvec3>& x, const std::vector<double>& kappa, const std::vector<dvec3>& boundary,
                          const std::vector<double>& psi, const std::vector<double>& kappa_b, const Params& params) {
    const CubicKernel kernel{params.h};
    const double rho0 = params.rest_density;
    Compact c{std::vector<double>(x.size(), 0.0), std::vector<double>(x.size(), 0.0)};
    for (size_t i = 0; i < x.size(); ++i) {
        for (size_t j = 0; j < x.size(); ++j) {
            if (j == i || glm::length(x[i] - x[j]) >= params.h) continue;
            const double w = params.mass * compact_weight(x[i] - x[j], kernel);
            c.change[i] += rho0 * w * (kappa[j] - kappa[i]);
            c.diagonal[i] += rho0 * w;
        }
        for (size_t b = 0; b < boundary.size(); ++b) {
            if (glm::length(x[i] - boundary[b]) >= params.h) continue;
            const double w = psi[b] * compact_weight(x[i] - boundary[b], kernel);
            c.change[i] += rho0 * w * (kappa_b[b] - kappa[i]);
            c.diagonal[i] += rho0 * w;
        }
    }
    return c;
}

std::vector<double> spreads(const std::vector<dvec3>& x, const std::vector<dvec3>& boundary, const std::vector<double>& psi,
                            const Params& params) {
    const CubicKernel kernel{params.h};
    std::vector<double> u(x.size());
    for (size_t i = 0; i < x.size(); ++i) {
        dvec3 sum(0.0);
        double magnitudes = 0.0;
        for (size_t j = 0; j < x.size(); ++j) {
            if (j == i || glm::length(x[i] - x[j]) >= params.h) continue;
            sum += params.mass * kernel.gradW(x[i] - x[j]);
            magnitudes += params.mass * glm::length(kernel.gradW(x[i] - x[j]));
        }
        for (size_t b = 0; b < boundary.size(); ++b) {
            if (glm::length(x[i] - boundary[b]) >= params.h) continue;
            sum += psi[b] * kernel.gradW(x[i] - boundary[b]);
            magnitudes += params.mass * glm::length(kernel.gradW(x[i] - boundary[b]));
        }
        u[i] = glm::length(sum) + magnitudes;
    }
    return u;
}

std::vector<bool> boundary_rows(const std::vector<dvec3>& x, const std::vector<dvec3>& boundary, const Params& params) {
    std::vector<bool> row(boundary.size(), false);
    for (size_t b = 0; b < boundary.size(); ++b)
        for (const dvec3& xi : x) row[b] = row[b] || glm::length(xi - boundary[b]) < params.h;
    return row;
}

Rows row_sources(Solve which, const std::vector<dvec3>& x, const std::vector<dvec3>& v, const std::vector<double>& u,
                 const std::vector<dvec3>& boundary, const std::vector<double>& psi, const Params& params, double dt) {
    const CubicKernel kernel{params.h};
    const std::vector<bool> row = boundary_rows(x, boundary, params);
    Rows r{std::vector<double>(boundary.size(), 0.0), std::vector<double>(boundary.size(), 0.0)};
    for (size_t b = 0; b < boundary.size(); ++b) {
        if (!row[b]) continue;
        double rho = 0.0, wall = 0.0, rate = 0.0, diagonal = 0.0;
        for (size_t j = 0; j < x.size(); ++j) {
            const double distance = glm::length(boundary[b] - x[j]);
            if (distance >= params.h) continue;
            const dvec3 g = kernel.gradW(boundary[b] - x[j]);
            rho += params.mass * kernel.W(distance);
            rate -= params.mass * glm::dot(v[j], g);
            diagonal += glm::length(g) * u[j];
        }
        for (size_t q = 0; q < boundary.size(); ++q) wall += psi[q] * kernel.W(glm::length(boundary[b] - boundary[q]));
        r.source[b] = which == Solve::density ? std::max(params.rest_density, wall) - (rho + wall + dt * rate) : -dt * rate;
        r.diagonal[b] = psi[b] * diagonal;
    }
    return r;
}

void correct_rows(const std::vector<dvec3>& x, const std::vector<dvec3>& a, const Rows& rows, const std::vector<dvec3>& boundary,
                  const Params& params, double omega_b, double dt, std::vector<double>& kappa_b) {
    const CubicKernel kernel{params.h};
    for (size_t b = 0; b < boundary.size(); ++b) {
        if (rows.diagonal[b] <= 0.0) continue;
        double change = 0.0;
        for (size_t j = 0; j < x.size(); ++j)
            if (glm::length(boundary[b] - x[j]) < params.h) change -= params.mass * glm::dot(a[j], kernel.gradW(boundary[b] - x[j]));
        const double residual = dt * dt * change - rows.source[b];
        kappa_b[b] = std::max(kappa_b[b] + omega_b * residual / (rows.diagonal[b] * dt * dt), 0.0);
    }
}

std::vector<double> extended_pressure(const std::vector<dvec3>& x, const std::vector<double>& kappa, const std::vector<dvec3>& boundary,
                                      const Params& params) {
    const CubicKernel kernel{params.h};
    std::vector<double> kappa_b(boundary.size(), 0.0);
    for (size_t b = 0; b < boundary.size(); ++b) {
        double weight = 0.0, extended = 0.0;
        for (size_t j = 0; j < x.size(); ++j) {
            const dvec3 d = boundary[b] - x[j];
            const double distance = glm::length(d);
            if (distance >= params.h) continue;
            const double w = kernel.W(distance);
            weight += w;
            extended += w * (kappa[j] + (kappa[j] > 0.0 ? glm::dot(params.gravity, d) / params.rest_density : 0.0));
        }
        kappa_b[b] = weight > 0.0 ? std::max(extended / weight, 0.0) : 0.0;
    }
    return kappa_b;
}

std::vector<double> handed_excess(const std::vector<dvec3>& x, const std::vector<dvec3>& a, const Rows& rows,
                                  const std::vector<dvec3>& boundary, const std::vector<double>& psi, const Params& params, double dt) {
    const CubicKernel kernel{params.h};
    std::vector<double> q(boundary.size(), 0.0);
    for (size_t b = 0; b < boundary.size(); ++b) {
        double change = 0.0, weight = 0.0;
        for (size_t j = 0; j < x.size(); ++j) {
            const double distance = glm::length(boundary[b] - x[j]);
            if (distance >= params.h) continue;
            change -= params.mass * glm::dot(a[j], kernel.gradW(boundary[b] - x[j]));
            weight += kernel.W(distance);
        }
        if (weight > 0.0) q[b] = psi[b] / params.mass * std::max(dt * dt * change - rows.source[b], 0.0) / weight;
    }
    return q;
}

std::vector<double> handed_to_fluid(const std::vector<dvec3>& x, const std::vector<dvec3>& boundary, const std::vector<double>& q,
                                    const Params& params) {
    const CubicKernel kernel{params.h};
    std::vector<double> handed(x.size(), 0.0);
    for (size_t i = 0; i < x.size(); ++i)
        for (size_t b = 0; b < boundary.size(); ++b) {
            const double distance = glm::length(x[i] - boundary[b]);
            if (distance < params.h) handed[i] += kernel.W(distance) * q[b];
        }
    return handed;
}

std::vector<double> eliminated_factors(const std::vector<dvec3>& x, const std::vector<dvec3>& boundary, const std::vector<double>& psi,
                                       const Params& params) {
    const CubicKernel kernel{params.h};
    std::vector<double> factor(x.size(), 0.0);
    for (size_t i = 0; i < x.size(); ++i) {
        dvec3 fluid(0.0), wall(0.0);
        double squares = 0.0;
        for (size_t j = 0; j < x.size(); ++j) {
            if (j == i || glm::length(x[i] - x[j]) >= params.h) continue;
            const dvec3 g = params.mass * kernel.gradW(x[i] - x[j]);
            fluid += g;
            squares += glm::dot(g, g);
        }
        for (size_t b = 0; b < boundary.size(); ++b)
            if (glm::length(x[i] - boundary[b]) < params.h) wall += psi[b] * kernel.gradW(x[i] - boundary[b]);
        const double diagonal = glm::length(fluid + wall) * glm::length(fluid + 2.0 * wall) + squares;
        factor[i] = diagonal > 0.0 ? 1.0 / diagonal : 0.0;
    }
    return factor;
}

std::vector<dvec3> pressure_accelerations(const std::vector<dvec3>& x, const std::vector<double>& kappa,
                                          const std::vector<dvec3>& boundary, const std::vector<double>& psi,
                                          const std::vector<double>& kappa_b, const Params& params) {
    const CubicKernel kernel{params.h};
    std::vector<dvec3> a(x.size(), dvec3(0.0));
    for (size_t i = 0; i < x.size(); ++i) {
        for (size_t j = 0; j < x.size(); ++j) a[i] -= params.mass * (kappa[i] + kappa[j]) * kernel.gradW(x[i] - x[j]);
        for (size_t b = 0; b < boundary.size(); ++b) a[i] -= psi[b] * (kappa[i] + kappa_b[b]) * kernel.gradW(x[i] - boundary[b]);
    }
    return a;
}

StepResult step(State& state, const std::vector<dvec3>& boundary, const std::vector<double>& psi, const Params& params,
                const Settings& s, double dt, bool divergence_solve) {
    const size_t n = state.x.size();
    state.kappa.resize(n, 0.0);
    state.kappa_v.resize(n, 0.0);
    StepResult r;
    r.density = densities(state.x, boundary, psi, params);
    const Factors f = factors(state.x, boundary, psi, params, s);
    const std::vector<dvec3> nonpressure = nonpressure_accelerations(state.x, state.v, boundary, psi, params, s);
    for (size_t i = 0; i < n; ++i) {
        state.kappa_v[i] = divergence_solve ? s.divergence_warm_start * state.kappa_v[i] : 0.0;
        state.kappa[i] *= s.warm_start;
    }
    if (divergence_solve)
        r.divergence = solve(Solve::divergence, state.x, state.v, r.density, f, state.kappa_v, boundary, psi, params, s, dt);
    for (size_t i = 0; i < n; ++i) state.v[i] += dt * nonpressure[i];
    r.density_solve = solve(Solve::density, state.x, state.v, r.density, f, state.kappa, boundary, psi, params, s, dt);
    r.pressure.resize(n);
    for (size_t i = 0; i < n; ++i) {
        state.x[i] += dt * state.v[i];
        r.pressure[i] = (state.kappa[i] + state.kappa_v[i]) * r.density[i] * r.density[i];
    }
    return r;
}

double time_step(const Params& params, double v_max, double a_max, double dt_max) {
    double dt = dt_max;
    if (v_max > 0.0) dt = std::min(dt, 0.4 * params.spacing / v_max);
    if (a_max > 0.0) dt = std::min(dt, 0.25 * std::sqrt(params.spacing / a_max));
    return dt;
}

}  // namespace ranryu::reference::dfsph
