// Checks of the DFSPH CPU reference itself (tests/reference/dfsph_reference.h) against analytic
// expectations, on fresh random inputs (seed in INFO): what the GPU passes are compared against has to
// be right first. docs/DFSPH.md (D3), (D6), (D12).
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include "reference/dfsph_reference.h"
#include "reference/random.h"

using glm::dvec3;
using namespace ranryu::reference;
namespace df = ranryu::reference::dfsph;

namespace {

// (D6)'s density change per dt², Σ_j m(a_i − a_j)·∇W_ij, a = a^p(κ) of (D3); no boundary.
std::vector<double> wide_change(const std::vector<dvec3>& x, const std::vector<double>& kappa, const Params& p) {
    const CubicKernel k{p.h};
    const std::vector<dvec3> a = df::pressure_accelerations(x, kappa, {}, {}, p, df::Settings{});
    std::vector<double> change(x.size(), 0.0);
    for (std::size_t i = 0; i < x.size(); ++i)
        for (std::size_t j = 0; j < x.size(); ++j) change[i] += p.mass * glm::dot(a[i] - a[j], k.gradW(x[i] - x[j]));
    return change;
}

}  // namespace

TEST_CASE("dfsph reference: the compact Laplacian (D12) is rho0^2 times a quadratic kappa's Laplacian on a lattice, and it "
          "sees the layer-to-layer alternation that (D3)'s density change cannot",
          "[reference][dfsph]") {
    Random rnd;
    INFO("seed " << rnd.seed);
    const double dx = rnd.uniform(0.005, 0.05);
    const Params p = Params::from_spacing(dx, rnd.uniform(500.0, 2000.0), 10.0, 1e-6, dvec3(0, -9.81, 0));
    const glm::ivec3 n(9);
    const dvec3 min = rnd.in_box(1.0);
    const std::vector<dvec3> x = lattice(min, n, dx);
    // The particles two or more spacings inside every face: their neighbours' neighbourhoods are whole.
    std::vector<std::size_t> inner;
    for (std::size_t i = 0; i < x.size(); ++i) {
        const glm::ivec3 c(glm::floor((x[i] - min) / dx));
        if (glm::all(glm::greaterThanEqual(c, glm::ivec3(2))) && glm::all(glm::lessThan(c, n - 2))) inner.push_back(i);
    }
    REQUIRE(inner.size() == 125);
    const double rho0 = p.rest_density;

    // kappa = q·|x − c|²/2 + g·x + k0: Laplacian 3q. The lattice's second moment of c_ij is not exactly the
    // continuum's: Σ_j m c_ij |x_ij|²/2 = 0.99155·3ρ0 on the cubic lattice at h = 2Δx (its shells r/Δx = 1,
    // √2, √3 summed in closed form below), so the compact change is 0.99155·3q·ρ0², to the roundings of
    // κ_j − κ_i (1e-7 relative); the linear part and k0 cancel pair by pair on the symmetric neighbourhood.
    const double q = rnd.uniform(1.0, 10.0), k0 = rnd.uniform(10.0, 100.0);
    const dvec3 c = min + rnd.uniform(0.3, 0.7) * dvec3(n) * dx, g = rnd.in_box(50.0);
    std::vector<double> quadratic(x.size());
    for (std::size_t i = 0; i < x.size(); ++i) quadratic[i] = 0.5 * q * glm::dot(x[i] - c, x[i] - c) + glm::dot(g, x[i]) + k0;
    const df::Compact smooth = df::compact_laplacian(x, quadratic, {}, {}, p);
    auto c_at = [&](double r) {   // c(r) r²/2 per unit mass, h = 2Δx, in units where Δx = 1
        const double h = 2.0, s = r / h, grad = s <= 0.5 ? s * (3.0 * s - 2.0) : -(1.0 - s) * (1.0 - s);
        return -2.0 * (48.0 / (std::numbers::pi * 16.0)) * grad * r / (r * r + 0.04) * r * r / 2.0;
    };
    const double moment = (6.0 * c_at(1.0) + 12.0 * c_at(std::sqrt(2.0)) + 8.0 * c_at(std::sqrt(3.0))) / 3.0;
    CHECK(moment == Approx(0.99155).epsilon(1e-4));
    const std::vector<double> wide = wide_change(x, quadratic, p);
    for (std::size_t i : inner) {
        INFO("particle " << i << ": compact " << smooth.change[i] << ", rho0^2 3q " << rho0 * rho0 * 3.0 * q << ", wide " << wide[i]);
        CHECK(smooth.change[i] == Approx(moment * 3.0 * q * rho0 * rho0).epsilon(1e-7));
        // (D6)'s wide operator approximates the same Laplacian (within 5 % on this lattice): the blend of
        // (D12) leaves a smooth pressure's density change as it was.
        CHECK(wide[i] == Approx(3.0 * q * rho0 * rho0).epsilon(0.05));
    }

    // kappa alternating from one x-y layer to the next about k0: (D3) puts no force on the inner particles
    // (each pair across adjacent layers carries κ_i + κ_j = 2k0, and the rest cancel by symmetry), so the
    // wide change is k0's alone, zero; the compact change is −2(κ_i − k0) times the adjacent layers'
    // share of C_i (0.464 of it on this lattice) and the rest nothing.
    const double amplitude = rnd.uniform(1.0, 10.0);
    std::vector<double> alternating(x.size());
    for (std::size_t i = 0; i < x.size(); ++i) {
        const int layer = int(std::floor((x[i].z - min.z) / dx));
        alternating[i] = k0 + (layer % 2 == 0 ? amplitude : -amplitude);
    }
    const df::Compact sharp = df::compact_laplacian(x, alternating, {}, {}, p);
    const std::vector<double> blind = wide_change(x, alternating, p);
    for (std::size_t i : inner) {
        INFO("particle " << i << ": compact " << sharp.change[i] << ", wide " << blind[i] << ", C_i " << sharp.diagonal[i]);
        CHECK(std::abs(blind[i]) <= 1e-9 * sharp.diagonal[i] * amplitude);
        CHECK(sharp.change[i] / (-2.0 * (alternating[i] - k0) * sharp.diagonal[i]) == Approx(0.464).epsilon(1e-3));
    }
}
