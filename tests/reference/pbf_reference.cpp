#include "reference/pbf_reference.h"

#include <cmath>

namespace ranryu::reference::pbf {

using glm::dvec3;

Settings Settings::from_keys(const Params& p, double relaxation, double k, double n, double dq, double xsph, double vorticity) {
    Settings s;
    s.epsilon = relaxation / (p.spacing * p.spacing);
    s.s_corr_scale = k * p.spacing * p.spacing;
    s.s_corr_n = n;
    s.w_dq = CubicKernel{p.h}.W(dq * p.h);
    s.xsph = xsph;
    s.vorticity = vorticity;
    return s;
}

Lambdas lambdas(const std::vector<dvec3>& x, const Neighbours& n, const std::vector<dvec3>& boundary, const std::vector<double>& psi,
                const Params& p, const Settings& s) {
    const CubicKernel k{p.h};
    Lambdas out{std::vector<double>(x.size()), std::vector<double>(x.size()), std::vector<double>(x.size())};
    for (std::size_t i = 0; i < x.size(); ++i) {
        double rho = 0.0, squares = 0.0;
        dvec3 grad(0.0);
        for (std::uint32_t j : n[i]) {   // (P2), (P4); j = i adds m W(0) and no gradient
            const dvec3 d = x[i] - x[j];
            rho += p.mass * k.W(glm::length(d));
            const dvec3 g = p.mass * k.gradW(d);
            grad += g;
            squares += glm::dot(g, g);
        }
        for (std::size_t b = 0; b < boundary.size(); ++b) {
            const dvec3 d = x[i] - boundary[b];
            rho += psi[b] * k.W(glm::length(d));
            grad += psi[b] * k.gradW(d);
        }
        const double c = std::max(rho / p.rest_density - 1.0, 0.0);                           // (P3)
        const double sum = (glm::dot(grad, grad) + squares) / (p.rest_density * p.rest_density);   // (P4)
        out.density[i] = rho;
        out.gradient_squares[i] = sum;
        out.lambda[i] = c > 0.0 ? -c / (sum + s.epsilon) : 0.0;
    }
    return out;
}

std::vector<dvec3> corrections(const std::vector<dvec3>& x, const std::vector<double>& lambda, const Neighbours& n,
                               const std::vector<dvec3>& boundary, const std::vector<double>& psi, const Params& p, const Settings& s) {
    const CubicKernel k{p.h};
    std::vector<dvec3> dx(x.size());
    for (std::size_t i = 0; i < x.size(); ++i) {
        dvec3 sum(0.0);
        for (std::uint32_t j : n[i]) {
            if (j == i) continue;
            const dvec3 d = x[i] - x[j];
            const double s_corr = -s.s_corr_scale * std::pow(k.W(glm::length(d)) / s.w_dq, s.s_corr_n);   // (P5)
            sum += p.mass * (lambda[i] + lambda[j] + s_corr) * k.gradW(d);
        }
        for (std::size_t b = 0; b < boundary.size(); ++b) sum += psi[b] * lambda[i] * k.gradW(x[i] - boundary[b]);
        dx[i] = sum / p.rest_density;   // (P6)
    }
    return dx;
}

std::vector<dvec3> xsph(const std::vector<dvec3>& x, const std::vector<dvec3>& v, const std::vector<double>& density,
                        const Neighbours& n, const Params& p, const Settings& s) {
    const CubicKernel k{p.h};
    std::vector<dvec3> out(x.size());
    for (std::size_t i = 0; i < x.size(); ++i) {
        dvec3 sum(0.0);
        for (std::uint32_t j : n[i])
            if (j != i) sum += (p.mass / density[j]) * k.W(glm::length(x[i] - x[j])) * (v[j] - v[i]);
        out[i] = v[i] + s.xsph * sum;
    }
    return out;
}

std::vector<dvec3> vorticities(const std::vector<dvec3>& x, const std::vector<dvec3>& v, const std::vector<double>& density,
                               const Neighbours& n, const Params& p) {
    const CubicKernel k{p.h};
    std::vector<dvec3> w(x.size());
    for (std::size_t i = 0; i < x.size(); ++i) {
        dvec3 sum(0.0);
        for (std::uint32_t j : n[i])
            if (j != i) sum += (p.mass / density[j]) * glm::cross(k.gradW(x[i] - x[j]), v[j] - v[i]);
        w[i] = sum;
    }
    return w;
}

std::vector<dvec3> confine_vorticity(const std::vector<dvec3>& x, const std::vector<dvec3>& v, const std::vector<dvec3>& omega,
                                     const std::vector<double>& density, const Neighbours& n, const Params& p, const Settings& s,
                                     double dt) {
    const CubicKernel k{p.h};
    std::vector<dvec3> out(v);
    for (std::size_t i = 0; i < x.size(); ++i) {
        dvec3 eta(0.0);
        for (std::uint32_t j : n[i])
            if (j != i) eta += (p.mass / density[j]) * (glm::length(omega[j]) - glm::length(omega[i])) * k.gradW(x[i] - x[j]);
        const double size = glm::length(eta);
        if (size > 0.0) out[i] += dt * s.vorticity * glm::cross(eta / size, omega[i]);
    }
    return out;
}

StepResult step(State& state, const std::vector<dvec3>& boundary, const std::vector<double>& psi, const Params& p, const Settings& s,
                double dt, int iterations, const Regather& regather) {
    std::vector<dvec3> x = state.x;
    for (std::size_t i = 0; i < x.size(); ++i) x[i] += dt * (state.v[i] + dt * p.gravity);   // (P1)
    const Neighbours fixed = neighbours(x, p.h);
    auto sets = [&](int pass) { return pass == 0 || !regather ? fixed : regather(x, fixed); };
    StepResult r{std::vector<double>(x.size()), std::vector<double>(x.size(), 0.0)};
    for (int it = 0; it < iterations; ++it) {
        const Neighbours n = sets(it);
        const Lambdas l = lambdas(x, n, boundary, psi, p, s);
        const std::vector<dvec3> dx = corrections(x, l.lambda, n, boundary, psi, p, s);
        for (std::size_t i = 0; i < x.size(); ++i) {
            x[i] += dx[i];
            r.pressure[i] -= p.rest_density * l.lambda[i] / (dt * dt);   // (P9)
        }
        r.density = l.density;
    }
    std::vector<dvec3> v(x.size());
    for (std::size_t i = 0; i < x.size(); ++i) v[i] = (x[i] - state.x[i]) / dt;   // (P7)
    const Neighbours n = sets(iterations);
    const std::vector<dvec3> omega = vorticities(x, v, r.density, n, p);   // of the velocities before XSPH
    v = xsph(x, v, r.density, n, p, s);
    if (s.vorticity > 0.0) v = confine_vorticity(x, v, omega, r.density, n, p, s, dt);
    state.x = x;
    state.v = v;
    return r;
}

}  // namespace ranryu::reference::pbf
