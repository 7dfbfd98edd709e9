// The density solve's coarse correction (docs/DFSPH.md (D12)): its three passes against the double
// CPU reference (tests/reference/dfsph_coarse_reference.h) on fresh random inputs, and what it is
// for: a compressed column's density solve converges in a few iterations with it, in hundreds without.
//
// Bounds. The restriction sums a cell's n_c residuals in float: |Δrhs_c| ≤ (n_c + 4) u Σ|e_i|/n_c ·
// H²/(ρ0 dt)² (n_c − 1 additions, then a division and three products). The fill fraction is a ratio
// of small integers: exact to u. Each of the S red-black sweeps rounds an update of e by a few u of
// the largest |e| (a sum of at most seven terms, a division, the mix): at most 8u a sweep, which the
// sweeps carry on undamped at worst: |Δe| ≤ 8 S u max|e| plus the right-hand sides' error times the
// solve's gain, which the same sweeps bound: S ω max|Δrhs| (a diagonal is at least 1). The
// prolongation interpolates e with eight weights in float: |Δκ| ≤ |Δe| + 16u max|e| + u|κ|.
#include "support/sph_rig.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include <catch2/catch.hpp>
#include <glm/glm.hpp>

#include "reference/dfsph_coarse_reference.h"
#include "support/reference_compare.h"

namespace {

namespace coarse = ranryu::reference::dfsph::coarse;
namespace gpu = ranryu::gpu;
using ranryu::test::kU;

// The tank at rest's column (docs/VALIDATION.md), 24 x 20 x 8 particles at 0.0125 m, DFSPH with the
// boundary rows (D9); `sph` adds keys to the "sph" object.
std::string column_json(const std::string& sph) {
    return R"({"model": "sph", "tank": {"min": [0, 0, 0], "max": [0.3, 0.4, 0.1]},
               "sph": {"solver": "dfsph", "viscosity": 1e-3, "max_iterations": 1000, )" + sph + R"(},
               "particles": {"spacing": 0.0125, "blocks": [{"min": [0, 0, 0], "max": [0.3, 0.25, 0.1]}]}})";
}

// The column compressed vertically to `pitch` dx (ρ ≈ ρ0/pitch), each particle moved by up to
// ±jitter·dx per axis, at rest; no particle within 1e-5 h of a face of the neighbour grid, where a
// float and a double division could put it in different cells.
std::vector<glm::vec4> column(ranryu::test::Random& rng, const ranryu::test::SphRig& rig, float pitch, float jitter) {
    const float dx = rig.scene.spacing;
    const auto& g = rig.fluid.grid().layout();
    for (int attempt = 0;; ++attempt) {
        REQUIRE(attempt < 100);
        std::vector<glm::vec4> x;
        bool ok = true;
        for (int k = 0; k < 8; ++k)
            for (int j = 0; j < 20; ++j)
                for (int i = 0; i < 24; ++i) {
                    const glm::vec3 wobble(rng.uniform(-jitter, jitter), rng.uniform(-jitter, jitter), rng.uniform(-jitter, jitter));
                    const glm::vec3 p = ((glm::vec3(float(i), float(j), float(k)) + 0.5f) * glm::vec3(1.0f, pitch, 1.0f) + wobble) * dx;
                    x.emplace_back(p, 0.0f);
                    const glm::dvec3 u = (glm::dvec3(p) - glm::dvec3(g.origin)) / double(g.cell);
                    const glm::dvec3 off = glm::abs(u - glm::round(u));
                    ok = ok && glm::all(glm::greaterThan(off, glm::dvec3(1e-5)));
                }
        if (ok) return x;
    }
}

// A step's stages up to the density solve's start, from `x` at rest and the warm start `warm`.
void open_density_solve(ranryu::test::SphRig& rig, const std::vector<glm::vec4>& x, const std::vector<glm::vec2>& warm, float dt,
                        int issued) {
    auto& d = rig.dfsph();
    d.set_issued_iterations(issued, 100);
    rig.fluid.upload_state(x, std::vector<glm::vec4>(x.size(), glm::vec4(0.0f)));
    d.upload_warm_start(warm);
    rig.fluid.set_fixed_dt(dt);
    rig.timer.begin_frame();
    rig.sim.begin_frame(0);
    rig.fluid.choose_time_step();
    rig.fluid.rebuild_grid();
    d.compute_density(rig.fluid);
    d.solve_divergence(rig.fluid);
    d.predict_density(rig.fluid);
}

coarse::Grid coarse_grid(const ranryu::test::SphRig& rig) {
    const auto& g = rig.fluid.grid().layout();
    return {{glm::dvec3(g.origin), double(g.cell), glm::ivec3(g.dims)}};
}

}  // namespace

TEST_CASE("dfsph coarse (D12): the restriction, the red-black sweeps and the prolongation match the reference", "[dfsph]") {
    ranryu::test::Random rng;
    INFO("seed " << rng.seed());
    const int sweeps = 10 + int(rng.below(51));
    INFO("sweeps " << sweeps);
    ranryu::test::SphRig rig(column_json(R"("chebyshev": 0, "coarse_sweeps": )" + std::to_string(sweeps)), "dfsph_coarse_test");
    auto& d = rig.dfsph();
    const std::vector<glm::vec4> x0 = column(rng, rig, 0.98f, 0.15f);
    std::vector<glm::vec2> warm(x0.size());
    for (auto& w : warm) w = glm::vec2(rng.uniform(0.0f, 0.02f), 0.0f);
    open_density_solve(rig, x0, warm, 2e-3f, 2);

    // The state the passes read: sorted positions, the sources, kappa with the rows' after it, and
    // residuals of both signs, smooth over the column plus noise, in the sorted order.
    const std::size_t n = rig.fluid.count(), nb = rig.fluid.boundary_count();
    const std::vector<glm::dvec3> x = ranryu::test::d3(rig.read(rig.fluid.positions()));
    const std::vector<glm::vec4> sources = rig.read(d.pressure_accelerations());
    const std::vector<float> before = d.kappa().read<float>(n + 2 * nb);
    std::vector<float> e(n);
    for (std::size_t i = 0; i < n; ++i) e[i] = float(40.0 * std::sin(10.0 * x[i].y + 3.0 * x[i].x)) + rng.uniform(-20.0f, 20.0f);
    d.upload_coarse_residuals(e);
    const float dt = rig.step().dt;
    d.correct_coarsely(rig.fluid);
    rig.timer.end_frame();

    std::vector<glm::dvec3> xb;
    std::vector<double> psi;
    rig.boundary(xb, psi);
    const coarse::Grid g = coarse_grid(rig);
    const gpu::SphParams& p = rig.fluid.params();
    std::vector<double> residual(e.begin(), e.end());
    coarse::Cells want = coarse::restrict_residual(g, x, residual, xb, double(p.spacing), double(p.rest_density), double(dt),
                                                   glm::dvec3(glm::vec3(p.domain_min)), glm::dvec3(glm::vec3(p.domain_max)));
    const std::vector<glm::vec4> got = d.coarse_grid().read<glm::vec4>(std::size_t(g.count()));

    // The restriction: every cell's kind and fill fraction, and the right-hand side of the active ones.
    std::vector<double> magnitude(std::size_t(g.count()), 0.0);
    std::vector<int> members(std::size_t(g.count()), 0);
    for (std::size_t i = 0; i < n; ++i) magnitude[g.index(g.cell_of(x[i]))] += std::abs(residual[i]), ++members[g.index(g.cell_of(x[i]))];
    const double H = g.cell(), scale = H * H / ((double(p.rest_density) * dt) * (double(p.rest_density) * dt));
    int active = 0, solid = 0;
    double rhs_error = 0.0, rhs_bound = 0.0;
    for (int k = 0; k < g.count(); ++k) {
        INFO("cell " << k << ": phi " << got[k].z << " against " << want.phi[k]);
        REQUIRE(std::abs(double(got[k].z) - want.phi[k]) <= 4.0 * kU * std::max(1.0, std::abs(want.phi[k])));
        if (!coarse::active(want.phi[k])) continue;
        ++active;
        const double bound = scale * (members[k] + 4) * kU * magnitude[k] / members[k];
        rhs_error = std::max(rhs_error, std::abs(double(got[k].y) - want.rhs[k]) / bound);
        rhs_bound = std::max(rhs_bound, bound);
        REQUIRE(std::abs(double(got[k].y) - want.rhs[k]) <= bound);
    }
    for (double phi : want.phi) solid += coarse::solid(phi) ? 1 : 0;
    INFO(active << " active and " << solid << " solid cells of " << g.count() << "; rhs error " << rhs_error << " of its bound");
    CHECK(active >= 20);   // the column spans 6 x 6 x 3 cells
    CHECK(solid > 0);

    // The sweeps.
    coarse::solve(g, want, sweeps, 1.5);
    double e_max = 0.0;
    for (int k = 0; k < g.count(); ++k) e_max = std::max(e_max, std::abs(want.e[k]));
    REQUIRE(e_max > 0.0);
    const double e_bound = 8.0 * sweeps * kU * e_max + sweeps * 1.5 * rhs_bound;
    for (int k = 0; k < g.count(); ++k) {
        if (!coarse::active(want.phi[k])) continue;
        INFO("cell " << k << ": e " << got[k].x << " against " << want.e[k] << " (bound " << e_bound << ", largest e " << e_max << ")");
        REQUIRE(std::abs(double(got[k].x) - want.e[k]) <= e_bound);
    }

    // The prolongation: every fluid particle but those that separate (their source above 1 % of rho0),
    // and every row of the step.
    const std::vector<float> after = d.kappa().read<float>(n + 2 * nb);
    const double k_bound = e_bound + 16.0 * kU * e_max;
    int corrected = 0;
    for (std::size_t i = 0; i < n; ++i) {
        const bool separates = double(sources[i].w) > 0.01 * double(p.rest_density);
        const double expect = separates ? double(before[i]) : std::max(double(before[i]) + coarse::correction_at(g, want, x[i]), 0.0);
        INFO("particle " << i << ": kappa " << before[i] << " -> " << after[i] << ", expected " << expect);
        REQUIRE(std::abs(double(after[i]) - expect) <= k_bound + kU * std::abs(expect));
        corrected += after[i] != before[i] ? 1 : 0;
    }
    CHECK(corrected > int(n / 2));
    gpu::BoundaryRowsState rows{};
    std::memcpy(&rows, d.boundary_rows().read<std::uint8_t>(sizeof rows).data(), sizeof rows);
    const std::vector<std::uint32_t> list = d.boundary_list().read<std::uint32_t>(rows.rows);
    std::vector<bool> listed(nb, false);
    for (std::uint32_t entry : list) listed[entry & ~0x80000000u] = true;
    REQUIRE(rows.rows > 0u);
    for (std::size_t b = 0; b < nb; ++b) {
        const double was = before[n + 2 * b], now = after[n + 2 * b];
        const double expect = listed[b] ? std::max(was + coarse::correction_at(g, want, xb[b]), 0.0) : was;
        INFO("boundary row " << b << ": kappa_b " << was << " -> " << now << ", expected " << expect);
        REQUIRE(std::abs(now - expect) <= k_bound + kU * std::abs(expect));
        REQUIRE(after[n + 2 * b + 1] == before[n + 2 * b + 1]);   // the divergence solve's kappa_v,b untouched
    }
    ranryu::test::require_no_gl_errors();
}

TEST_CASE("dfsph coarse (D12): a compressed column's density solve converges in a few iterations with it, not in hundreds without",
          "[dfsph]") {
    ranryu::test::Random rng;
    INFO("seed " << rng.seed());
    // The column on its lattice compressed to 1.03-1.05 rho0, from no pressure, one step of 2 ms: the
    // pressure it needs is a parabola over its 20 layers (docs/DFSPH.md (D12)), the longest wavelength
    // there is, which relaxed Jacobi shortens by a factor close to 1 an iteration. On the lattice the
    // residual is smooth; a disordered column is where the correction does not help (docs/DFSPH.md
    // (D12), "Where it fails").
    const float pitch = rng.uniform(0.975f, 0.985f);
    INFO("pitch " << pitch);
    std::vector<glm::vec4> x;
    auto solve = [&](int sweeps, int issued) {
        ranryu::test::SphRig rig(column_json(R"("chebyshev": 0, "coarse_sweeps": )" + std::to_string(sweeps)), "dfsph_coarse_test");
        if (x.empty()) x = column(rng, rig, pitch, 0.0f);
        open_density_solve(rig, x, std::vector<glm::vec2>(x.size(), glm::vec2(0.0f)), 2e-3f, issued);
        rig.dfsph().solve_density(rig.fluid);
        rig.timer.end_frame();
        return rig.step();
    };
    const gpu::StepState with = solve(40, 100), without = solve(0, 200);
    INFO("with the correction: " << with.iterations.x << " iterations, error " << with.error.x << "; without: " << without.iterations.x
                                 << " iterations, error " << without.error.x);
    CHECK(with.unconverged.x == 0u);
    CHECK(with.iterations.x <= 12u);
    CHECK(without.unconverged.x == 1u);   // 200 iterations did not reach eta
    CHECK(double(without.error.x) > 2.0 * double(with.error.x));
    ranryu::test::require_no_gl_errors();
}


