// The PBF passes of glsl/sim/pbf/ (driven through sim::Pbf's stages) against the double-precision CPU
// reference of docs/PBF.md (tests/reference/pbf_reference.h), on fresh random states: jittered,
// compressed lattices with random velocities, uploaded and read back after each stage. The reference
// starts every stage from what the GPU read back, so each difference is the float rounding of the
// stage under test; one whole step is also compared from its start. Last, a resting column run two
// seconds at the defaults must settle within stated density and speed bounds.
//
// Tolerances, as in dfsph_test.cpp: the GPU works in float (unit roundoff u = 2^-24), the reference
// in double. A sum of N terms t_k, each computed with relative error at most c·u, is off by at most
// (N + c)·u·Σ|t_k| (Higham 2002 §4.2, first order), c = 16 for a kernel value or gradient times a
// few products. Each check names the sum it bounds.
#include "support/gl_fixture.h"
#include "support/reference_compare.h"
#include "support/sph_rig.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "reference/pbf_reference.h"
#include "reference/sph_reference.h"
#include "scene/scene.h"
#include "shared/bindings.h"

namespace {

namespace ref = ranryu::reference;
namespace pb = ranryu::reference::pbf;
namespace gpu = ranryu::gpu;
using glm::dvec3;

using namespace ranryu::test;   // kU, kC (see the header), d3, vec_error, flags_of: support/reference_compare.h

// 512 fluid particles (an 8x8x8 block at spacing 0.03 m) in a cubic tank of side 0.3 m, PBF with two
// iterations a step and a strong XSPH (so its sum is well above rounding); `pbf` adds keys to "sph.pbf",
// `sph` to "sph".
std::string scene_json(const std::string& pbf = "", const std::string& sph = "") {
    return R"({"model": "sph", "tank": {"min": [0, 0, 0], "max": [0.3, 0.3, 0.3]},
               "sph": {"solver": "pbf", )" + (sph.empty() ? "" : sph + ", ") + R"("pbf": {"substeps": 4, "iterations": 2, "xsph": 0.1)" +
           (pbf.empty() ? "" : ", " + pbf) + R"(}},
               "particles": {"spacing": 0.03, "blocks": [{"min": [0, 0, 0], "max": [0.24, 0.24, 0.24]}]}})";
}


struct Rig : ranryu::test::SphRig {
    explicit Rig(const std::string& pbf = "", const std::string& sph = "") : SphRig(scene_json(pbf, sph), "pbf_test") {}
    ref::Params params() const {
        const gpu::SphParams& p = fluid.params();
        return ref::Params::from_spacing(double(p.spacing), double(p.rest_density), 0.0, double(p.viscosity),
                                         dvec3(glm::vec3(p.gravity)));
    }
    pb::Settings settings() const {
        const ranryu::scene::PbfSettings& s = scene.sph.pbf;
        return pb::Settings::from_keys(params(), s.relaxation, s.s_corr_k, s.s_corr_n, s.s_corr_dq, s.xsph, s.vorticity);
    }
    std::vector<double> read_doubles(const ranryu::gl::Buffer& b) const {
        const std::vector<float> f = b.read<float>(fluid.count());
        return std::vector<double>(f.begin(), f.end());
    }
};

// The block on a lattice of pitch `ratio`·dx at `corner`, jittered by ±`jitter`·dx, velocities in
// ±`speed`; no pair of predicted positions x + dt(v + dt g) within 1e-5·h of h (float and double
// would disagree on a neighbour).
void block_state(ranryu::test::Random& rng, const Rig& rig, glm::vec3 corner, float ratio, float jitter, float speed, float dt,
                 std::vector<glm::vec4>& x, std::vector<glm::vec4>& v) {
    const float dx = rig.scene.spacing;
    const double h = 2.0 * double(dx);
    const dvec3 g(rig.scene.gravity);
    REQUIRE(rig.fluid.count() == 512);
    for (int attempt = 0;; ++attempt) {
        REQUIRE(attempt < 100);
        x.clear(), v.clear();
        for (int k = 0; k < 8; ++k)
            for (int j = 0; j < 8; ++j)
                for (int i = 0; i < 8; ++i) {
                    const glm::vec3 w(rng.uniform(-jitter, jitter), rng.uniform(-jitter, jitter), rng.uniform(-jitter, jitter));
                    x.emplace_back(corner + ((glm::vec3(float(i), float(j), float(k)) + 0.5f) * ratio + w) * dx, 0.0f);
                    v.emplace_back(rng.uniform(-speed, speed), rng.uniform(-speed, speed), rng.uniform(-speed, speed), 0.0f);
                }
        std::vector<dvec3> p(x.size());
        for (std::size_t i = 0; i < x.size(); ++i) p[i] = d3(x[i]) + double(dt) * (d3(v[i]) + double(dt) * g);
        bool ok = true;
        for (std::size_t a = 0; a < p.size() && ok; ++a)
            for (std::size_t b = a + 1; b < p.size() && ok; ++b) ok = std::abs(glm::length(p[a] - p[b]) - h) >= 1e-5 * h;
        if (ok) return;
    }
}

// Per particle, over fluid neighbours j != i (of `n`) and every boundary b: Σ m|∇W|, Σ psi|∇W|,
// Σ m²|∇W|², and the number of terms.
struct Magnitudes {
    std::vector<double> fluid, wall, squares;
    std::vector<int> terms;
};
Magnitudes magnitudes(const std::vector<dvec3>& x, const pb::Neighbours& n, const std::vector<dvec3>& xb, const std::vector<double>& psi,
                      const ref::Params& p) {
    const ref::CubicKernel k{p.h};
    const std::size_t N = x.size();
    Magnitudes m{std::vector<double>(N, 0.0), std::vector<double>(N, 0.0), std::vector<double>(N, 0.0), std::vector<int>(N, 0)};
    for (std::size_t i = 0; i < N; ++i) {
        for (std::uint32_t j : n[i]) {
            if (j == i) continue;
            const double g = p.mass * glm::length(k.gradW(x[i] - x[j]));
            m.fluid[i] += g, m.squares[i] += g * g, ++m.terms[i];
        }
        for (std::size_t b = 0; b < xb.size(); ++b)
            if (glm::length(x[i] - xb[b]) < p.h) m.wall[i] += psi[b] * glm::length(k.gradW(x[i] - xb[b])), ++m.terms[i];
    }
    return m;
}

// The stages of one step of two iterations on the state (x, v), everything read back after each.
struct Stages {
    std::vector<glm::vec4> start, v0, xstar, density1, x1, density2, x2, xproj, vstep, vend, omega;
    // With the warm start (P10), which starts from `warm` (the upload's order): the prediction and
    // PbfWarm before the sort, PbfWarm after it (d_i), and at the step's end (a^p_i).
    std::vector<glm::vec4> xstar_unsorted, warm_predicted, warm_sorted, warm_end;
    std::vector<double> lambda1, lambda2;
    float dt = 0.0f;
    std::uint32_t max_density = 0;   // StepState.frame_max_density: the bits of the largest ρ/ρ0 recorded
};

// With `walk_boundary` the boundary masks' origins are moved a metre away after the first lambda
// pass, so that no later walk may read the masks (glsl/sim/pbf/pbf.glsl boundary_masks_hold): every
// particle walks the boundary's cells.
Stages run_stages(Rig& rig, const std::vector<glm::vec4>& x, const std::vector<glm::vec4>& v, float dt,
                  const std::vector<glm::vec4>& warm = {}, bool walk_boundary = false) {
    Stages s;
    auto& pbf = rig.pbf();
    REQUIRE(pbf.iterations() == 2);
    const bool warm_start = pbf.params().warm_start > 0.0f;
    rig.fluid.upload_state(x, v);
    if (warm_start) pbf.warm().upload(warm.data(), warm.size() * sizeof(glm::vec4));
    rig.fluid.set_fixed_dt(dt);
    rig.timer.begin_frame();
    rig.sim.begin_frame(0);
    rig.fluid.choose_time_step();
    pbf.predict(rig.fluid);
    if (warm_start) {
        s.xstar_unsorted = rig.read(rig.fluid.positions());
        s.warm_predicted = rig.read(pbf.warm());
    }
    rig.fluid.rebuild_grid();
    if (warm_start) s.warm_sorted = rig.read(pbf.warm());
    s.start = rig.read(pbf.start());
    s.v0 = rig.read(rig.fluid.velocities());
    s.xstar = rig.read(rig.fluid.positions());
    pbf.compute_lambda(rig.fluid, true, false);
    if (walk_boundary) {
        std::vector<glm::vec4> origins = rig.read(pbf.mask_origins());
        for (glm::vec4& o : origins) o += glm::vec4(1.0f, 1.0f, 1.0f, 0.0f);
        pbf.mask_origins().upload(origins.data(), origins.size() * sizeof(glm::vec4));
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
    s.density1 = rig.read(rig.fluid.densities());
    s.lambda1 = rig.read_doubles(pbf.lambda());
    pbf.correct_positions(rig.fluid);
    s.x1 = rig.read(rig.fluid.positions());
    pbf.compute_lambda(rig.fluid, false, true);
    s.density2 = rig.read(rig.fluid.densities());
    s.lambda2 = rig.read_doubles(pbf.lambda());
    pbf.correct_positions(rig.fluid);
    s.x2 = rig.read(rig.fluid.positions());
    pbf.update_velocities(rig.fluid);
    s.xproj = rig.read(rig.fluid.positions());
    s.vstep = rig.read(pbf.step_velocities());
    if (warm_start) s.warm_end = rig.read(pbf.warm());
    pbf.apply_viscosity(rig.fluid);
    s.vend = rig.read(rig.fluid.velocities());
    if (pbf.params().vorticity > 0.0f) s.omega = rig.read(pbf.vorticity());
    s.dt = rig.step().dt;
    s.max_density = rig.step().frame_max_density;
    rig.sim.end_frame();
    rig.timer.end_frame();
    rig.finish();
    return s;
}

// The fluid neighbours the GPU's passes after the first λ pass visit (neighbours.glsl, docs/PBF.md
// "A step"): a particle whose neighbour masks are complete (the first pass's flag kMasksComplete)
// visits the set N found on x*; the others walk the cells around their sorted cell, that of x*, and
// take the particles within h at the pass's positions.
pb::Regather gpu_rule(const Rig& rig, const std::vector<glm::vec4>& xstar, const std::vector<glm::vec4>& density1) {
    const ranryu::sim::GridLayout& g = rig.fluid.grid().layout();
    const std::size_t N = xstar.size();
    std::vector<glm::ivec3> cell(N);
    std::vector<bool> masked(N);
    for (std::size_t i = 0; i < N; ++i) {
        const glm::ivec3 c(glm::floor((glm::vec3(xstar[i]) - g.origin) / g.cell));   // grid.glsl's grid_cell, in float
        cell[i] = glm::clamp(c, glm::ivec3(0), glm::ivec3(g.dims) - 1);
        masked[i] = (flags_of(density1[i]) & 1u) != 0u;
    }
    const double h = 2.0 * double(rig.scene.spacing);
    return [cell, masked, h](const std::vector<dvec3>& x, const pb::Neighbours& fixed) {
        pb::Neighbours n(x.size());
        for (std::size_t i = 0; i < x.size(); ++i) {
            if (masked[i]) {
                n[i] = fixed[i];
                continue;
            }
            for (std::size_t j = 0; j < x.size(); ++j) {
                const glm::ivec3 d = glm::abs(cell[i] - cell[j]);
                if (j == i || (d.x <= 1 && d.y <= 1 && d.z <= 1 && glm::length(x[i] - x[j]) < h)) n[i].push_back(std::uint32_t(j));
            }
        }
        return n;
    };
}

// One step of 2 ms on a fresh block at `corner`, a lattice of pitch `ratio`·dx jittered by ±0.15 dx,
// velocities in ±0.5 m/s (compressed where ratio < 1, moving a sixth of a spacing a step).
Stages random_step(ranryu::test::Random& rng, Rig& rig, glm::vec3 corner, float ratio) {
    const float dt = 2e-3f;
    std::vector<glm::vec4> x, v;
    block_state(rng, rig, corner, ratio, 0.15f, 0.5f, dt, x, v);
    Stages s = run_stages(rig, x, v, dt);
    REQUIRE(double(s.dt) == Approx(double(dt)).epsilon(1e-6));
    return s;
}

// (P2)-(P4) at positions x with the GPU's density and lambda: returns how many particles were
// compressed (C > 0). `rho_in` are the GPU's densities.
int check_lambda(const char* what, const std::vector<dvec3>& x, const pb::Neighbours& n, const std::vector<dvec3>& xb, const std::vector<double>& psi,
                 const ref::Params& p, const pb::Settings& set, const std::vector<glm::vec4>& density, const std::vector<double>& lambda) {
    const pb::Lambdas want = pb::lambdas(x, n, xb, psi, p, set);
    const Magnitudes m = magnitudes(x, n, xb, psi, p);
    const double rho2 = p.rest_density * p.rest_density;
    int compressed = 0;
    for (std::size_t i = 0; i < x.size(); ++i) {
        INFO(what << ", particle " << i << " at " << x[i].x << " " << x[i].y << " " << x[i].z << ", flags " << flags_of(density[i]));
        const double terms = double(m.terms[i]) + 1.0 + kC;
        // (P2): a sum of positive terms, ρ itself their magnitude.
        const double e_rho = terms * kU * want.density[i];
        CHECK(std::abs(double(density[i].x) - want.density[i]) <= e_rho);
        // (P4): the gradient sum is off by e_g = terms·u·G (G = Σ m|∇W| + Σ psi|∇W|); its square by
        // 2|grad|e_g + e_g², and the squares by terms·u·Σ m²|∇W|²; a division and a sum add a few u.
        const double G = m.fluid[i] + m.wall[i], e_g = terms * kU * G;
        const double grad = std::sqrt(std::max(want.gradient_squares[i] * rho2 - m.squares[i], 0.0));
        const double e_s = (2.0 * grad * e_g + e_g * e_g + terms * kU * m.squares[i]) / rho2 + 4.0 * kU * want.gradient_squares[i];
        // λ = −C/(S + ε): C carries e_rho/ρ0, S carries e_s.
        const double denom = want.gradient_squares[i] + set.epsilon;
        const double e_l = (e_rho / p.rest_density) / denom + std::abs(want.lambda[i]) * e_s / denom + 4.0 * kU * std::abs(want.lambda[i]);
        CHECK(std::abs(lambda[i] - want.lambda[i]) <= e_l);
        CHECK(double(density[i].z) == lambda[i]);
        compressed += want.lambda[i] < 0.0;
    }
    return compressed;
}

// (P5), (P6): x_next = x + Δx(x, λ) with the GPU's λ; returns the largest bound used.
double check_correction(const char* what, const std::vector<dvec3>& x, const std::vector<glm::vec4>& x_next, const std::vector<double>& lambda,
                        const pb::Neighbours& n, const std::vector<dvec3>& xb, const std::vector<double>& psi, const ref::Params& p,
                        const pb::Settings& set) {
    const std::vector<dvec3> dx = pb::corrections(x, lambda, n, xb, psi, p, set);
    const ref::CubicKernel k{p.h};
    double largest = 0.0;
    for (std::size_t i = 0; i < x.size(); ++i) {
        INFO(what << ", particle " << i);
        // Σ m(|λ_i| + |λ_j| + |s_corr|)|∇W|/ρ0 + Σ psi|λ_i||∇W|/ρ0, each term c·u (pow's rounding
        // scaled by n is in c), then the addition to x.
        double size = 0.0;
        int terms = 0;
        for (std::uint32_t j : n[i]) {
            if (j == i) continue;
            const dvec3 d = x[i] - x[j];
            const double s_corr = set.s_corr_scale * std::pow(k.W(glm::length(d)) / set.w_dq, set.s_corr_n);
            size += p.mass * (std::abs(lambda[i]) + std::abs(lambda[j]) + (1.0 + set.s_corr_n) * s_corr) * glm::length(k.gradW(d));
            ++terms;
        }
        for (std::size_t b = 0; b < xb.size(); ++b)
            if (glm::length(x[i] - xb[b]) < p.h) size += psi[b] * std::abs(lambda[i]) * glm::length(k.gradW(x[i] - xb[b])), ++terms;
        const dvec3 want = x[i] + dx[i];
        const double bound = (double(terms) + kC) * kU * size / p.rest_density + 2.0 * kU * glm::length(want);
        largest = std::max(largest, bound);
        CHECK(vec_error(x_next[i], want) <= bound);
    }
    return largest;
}

}  // namespace

TEST_CASE("pbf: the prediction, lambda and the position correction of both iterations match the reference", "[pbf]") {
    ranryu::test::Random rng;
    INFO("seed " << rng.seed());
    // A compressed block against the floor and two walls (boundary terms), another in mid-tank.
    const glm::vec3 corner = GENERATE(glm::vec3(0.0f), glm::vec3(0.02f, 0.03f, 0.025f));
    INFO("block at " << corner.x << " " << corner.y << " " << corner.z);
    // The neighbour grid's variants: with masks every particle with a complete mask keeps the first
    // pass's set and the rest walk around their sorted cell; with Morton keys that cell comes from
    // key_cell()'s decoding; without masks every particle walks, from its sorted cell, in every pass.
    const std::string grid = GENERATE(std::string(), std::string(R"("neighbour_keys": "morton")"),
                                      std::string(R"("neighbour_masks": false)"));
    INFO("grid: " << (grid.empty() ? "linear keys, masks" : grid));
    Rig rig("", grid);
    const Stages s = random_step(rng, rig, corner, 0.95f);

    const ref::Params p = rig.params();
    const pb::Settings set = rig.settings();
    std::vector<dvec3> xb;
    std::vector<double> psi;
    rig.boundary(xb, psi);
    const std::size_t N = s.start.size();
    // (P1): x* = x + dt (v + dt g), g the first step's non-pressure acceleration.
    const double dtd = double(s.dt);
    for (std::size_t i = 0; i < N; ++i) {
        const dvec3 want = d3(s.start[i]) + dtd * (d3(s.v0[i]) + dtd * p.gravity);
        CHECK(vec_error(s.xstar[i], want) <= 4.0 * kU * (glm::length(want) + dtd * glm::length(d3(s.v0[i])) + dtd * dtd * glm::length(p.gravity)));
    }
    // The first iteration on x*, with the neighbour sets found there; the second on the moved positions
    // with the same sets.
    const std::vector<dvec3> xstar = d3(s.xstar), x1 = d3(s.x1);
    const pb::Neighbours n = ref::neighbours(xstar, p.h), n1 = gpu_rule(rig, s.xstar, s.density1)(x1, n);
    const int compressed = check_lambda("first iteration", xstar, n, xb, psi, p, set, s.density1, s.lambda1);
    check_correction("first iteration", xstar, s.x1, s.lambda1, n, xb, psi, p, set);
    check_lambda("second iteration", x1, n1, xb, psi, p, set, s.density2, s.lambda2);
    check_correction("second iteration", x1, s.x2, s.lambda2, n1, xb, psi, p, set);
    // (P9): p = −ρ0 Σλ/dt², summed in float over the two iterations.
    for (std::size_t i = 0; i < N; ++i) {
        const double p1 = -p.rest_density * s.lambda1[i] / (dtd * dtd), p2 = p1 - p.rest_density * s.lambda2[i] / (dtd * dtd);
        CHECK(std::abs(double(s.density1[i].y) - p1) <= 4.0 * kU * std::abs(p1));
        CHECK(std::abs(double(s.density2[i].y) - p2) <= 8.0 * kU * (std::abs(p1) + std::abs(p2)));
    }
    // The guard records the largest ρ/ρ0 of the last iteration's λ pass, not the prediction's.
    // The shader's rho/rho0 is GLSL's division, within 2.5 ulp of the quotient (GLSL 4.30 §4.7.1; NVIDIA's
    // is not IEEE's, llvmpipe's is): the CPU's float quotient of the same densities within 3 ulp.
    float largest = 0.0f;
    for (std::size_t i = 0; i < N; ++i) largest = std::max(largest, s.density2[i].x / rig.fluid.params().rest_density);
    float recorded;
    std::memcpy(&recorded, &s.max_density, sizeof recorded);
    INFO("recorded " << recorded << ", the CPU's " << largest);
    CHECK(std::abs(recorded - largest) <= 3.0f * (std::nextafter(largest, 2.0f * largest) - largest));
    // The states exercise what they are meant to: most of the compressed block has a constraint to
    // meet, and the correction reduced the compression.
    CHECK(compressed > int(N) / 2);
    double before = 0.0, after = 0.0;
    for (std::size_t i = 0; i < N; ++i) before += double(s.density1[i].x), after += double(s.density2[i].x);
    CHECK(after < before);
    ranryu::test::require_no_gl_errors();
}

TEST_CASE("pbf: the boundary's masks with their skin give the walk's sums, bit for bit", "[pbf]") {
    ranryu::test::Random rng;
    INFO("seed " << rng.seed());
    // A compressed block in the tank's corner (the floor and two walls), moving: one step read through
    // the masks where a particle stays within the skin of x*, and one with every boundary walked.
    Rig masked, walked;
    const float dt = 2e-3f;
    std::vector<glm::vec4> x, v;
    block_state(rng, masked, glm::vec3(0.0f), 0.9f, 0.15f, 1.0f, dt, x, v);
    const Stages a = run_stages(masked, x, v, dt), b = run_stages(walked, x, v, dt, {}, true);
    REQUIRE(a.xstar == b.xstar);
    CHECK(a.density2 == b.density2);
    CHECK(a.x2 == b.x2);
    CHECK(a.vend == b.vend);
    // Both ways ran in the masked step: particles near a wall that stayed within the skin (0.99 h/4) of
    // x* read the masks, those the correction carried beyond it walked (about 180-220 and 50-100 of 275).
    const std::vector<glm::vec4> origins = masked.read(masked.pbf().mask_origins());
    const double h = double(masked.fluid.params().h), skin = 0.99 * 0.25 * h;
    std::size_t near = 0, held = 0, moved = 0;
    for (std::size_t i = 0; i < a.x1.size(); ++i) {
        if (!(flags_of(a.density1[i]) & 2u)) continue;   // kBoundaryNear
        ++near;
        const double d = glm::length(d3(a.x1[i]) - d3(origins[i]));
        held += d <= skin;
        moved += d > skin;
    }
    INFO(near << " particles near a wall: " << held << " within the skin after the first correction, " << moved << " beyond it");
    CHECK(held > 0);
    CHECK(moved > 0);
    ranryu::test::require_no_gl_errors();
}

TEST_CASE("pbf: the step's velocities, XSPH and vorticity confinement match the reference", "[pbf]") {
    ranryu::test::Random rng;
    INFO("seed " << rng.seed());
    const bool vorticity = GENERATE(false, true);
    INFO("vorticity confinement " << (vorticity ? "on" : "off"));
    Rig rig(vorticity ? R"("vorticity": 2.0)" : "");
    const Stages s = random_step(rng, rig, glm::vec3(0.02f, 0.03f, 0.025f), 0.97f);

    const ref::Params p = rig.params();
    const pb::Settings set = rig.settings();
    const ref::CubicKernel k{p.h};
    const double dtd = double(s.dt);
    const std::size_t N = s.start.size();
    const std::vector<dvec3> xs = d3(s.xproj), vs = d3(s.vstep);
    const pb::Neighbours n = gpu_rule(rig, s.xstar, s.density1)(xs, ref::neighbours(d3(s.xstar), p.h));
    std::vector<double> rho(N);
    for (std::size_t i = 0; i < N; ++i) rho[i] = double(s.density2[i].x);
    // (P7): v = (x − x_n)/dt, the block in mid-tank far from every wall (no projection).
    for (std::size_t i = 0; i < N; ++i) {
        REQUIRE(s.xproj[i] == s.x2[i]);
        const dvec3 x0 = d3(s.start[i]), want = (d3(s.x2[i]) - x0) / dtd;
        CHECK(vec_error(s.vstep[i], want) <= (2.0 * kU * (glm::length(x0) + glm::length(d3(s.x2[i])))) / dtd + 4.0 * kU * glm::length(want));
    }
    // (P7) XSPH: c Σ (m/ρ_j) W |v_j − v_i|, each term c·u; (P8) ω: Σ (m/ρ_j)|∇W||v_j − v_i|.
    const std::vector<dvec3> smooth = pb::xsph(xs, vs, rho, n, p, set);
    const std::vector<dvec3> omega = pb::vorticities(xs, vs, rho, n, p);
    std::vector<double> e_smooth(N, 0.0), e_omega(N, 0.0), size_w(N, 0.0);
    for (std::size_t i = 0; i < N; ++i) {
        double w = 0.0, g = 0.0;
        int terms = 0;
        for (std::uint32_t j : n[i]) {
            if (j == i) continue;
            const dvec3 d = xs[i] - xs[j];
            const double vol = p.mass / rho[j], dv = glm::length(vs[j] - vs[i]);
            w += vol * k.W(glm::length(d)) * dv, g += vol * glm::length(k.gradW(d)) * dv, ++terms;
        }
        e_smooth[i] = set.xsph * (double(terms) + kC) * kU * w + 4.0 * kU * glm::length(smooth[i]);
        e_omega[i] = (double(terms) + kC) * kU * g;
    }
    if (!vorticity) {
        for (std::size_t i = 0; i < N; ++i) CHECK(vec_error(s.vend[i], smooth[i]) <= e_smooth[i]);
    } else {
        for (std::size_t i = 0; i < N; ++i) {
            CHECK(vec_error(s.omega[i], omega[i]) <= e_omega[i]);
            CHECK(std::abs(double(s.omega[i].w) - glm::length(d3(s.omega[i]))) <= 4.0 * kU * double(s.omega[i].w));
        }
        // (P8) with the GPU's ω: η = Σ (m/ρ_j)(|ω_j| − |ω_i|)∇W is off by e_eta; the direction
        // N = η/|η| by about 2·e_eta/|η| where that is small (particles where it is not are skipped:
        // their direction is not determined by the data), and dt·ε·|ω| scales it.
        const std::vector<dvec3> w_gpu = d3(s.omega);
        const std::vector<dvec3> want = pb::confine_vorticity(xs, smooth, w_gpu, rho, n, p, set, dtd);
        std::size_t checked = 0;
        for (std::size_t i = 0; i < N; ++i) {
            dvec3 eta(0.0);
            double size = 0.0;
            int terms = 0;
            for (std::uint32_t j : n[i]) {
                if (j == i) continue;
                const dvec3 g = (p.mass / rho[j]) * k.gradW(xs[i] - xs[j]);
                eta += (glm::length(w_gpu[j]) - glm::length(w_gpu[i])) * g;
                size += (glm::length(w_gpu[j]) + glm::length(w_gpu[i])) * glm::length(g), ++terms;
            }
            const double e_eta = (double(terms) + kC) * kU * size, eta_n = glm::length(eta);
            if (e_eta > 0.01 * eta_n) continue;
            ++checked;
            const double e_dir = 2.0 * e_eta / eta_n + 4.0 * kU;
            CHECK(vec_error(s.vend[i], want[i]) <= e_smooth[i] + dtd * set.vorticity * glm::length(w_gpu[i]) * e_dir + 4.0 * kU * glm::length(want[i]));
        }
        CHECK(checked > N * 9 / 10);
        // The confinement did something measurable.
        double moved = 0.0;
        for (std::size_t i = 0; i < N; ++i) moved = std::max(moved, glm::length(want[i] - smooth[i]));
        CHECK(moved > 1e3 * kU);
    }
    ranryu::test::require_no_gl_errors();
}

TEST_CASE("pbf: the warm start (P10) adds w a^p to the prediction and leaves the step's capped pressure acceleration", "[pbf]") {
    ranryu::test::Random rng;
    INFO("seed " << rng.seed());
    Rig rig(R"("warm_start": 0.75)");
    // A block 0.5 % compressed, jittered by ±0.03 dx, at up to 0.05 m/s, over a step of 4 ms (the
    // scene's frame_dt / 4): corrections of the order of the cap's 2 g dt² = 0.3 mm, some above it and
    // some below.
    const float dt = 4e-3f;
    std::vector<glm::vec4> x, v;
    block_state(rng, rig, glm::vec3(0.02f, 0.03f, 0.025f), 0.995f, 0.03f, 0.05f, dt, x, v);
    // The last step's a^p: random, up to 1.5 |g| (below the cap).
    const double g = 9.81, w = 0.75, cap = RANRYU_PBF_WARM_CAP * g;
    std::vector<glm::vec4> warm(x.size());
    for (glm::vec4& a : warm) a = glm::vec4(rng.uniform(-0.85f, 0.85f), rng.uniform(-0.85f, 0.85f), rng.uniform(-0.85f, 0.85f), 0.0f) * float(g);
    const Stages s = run_stages(rig, x, v, dt, warm);
    const double dtd = double(s.dt), u = kU;
    REQUIRE(dtd == Approx(double(dt)).epsilon(1e-6));
    // The prediction (P1) with (P10): x* = x + dt(v + dt(g + w a^p)); float: each of the few products and
    // sums rounds once (a few u of |x| + dt|v| + dt²|a|), |x| ≤ 0.3 m. PbfWarm then holds
    // d = x* − x − w a^p dt², the same roundings over again.
    const dvec3 gravity(0.0, -g, 0.0);
    for (std::size_t i = 0; i < x.size(); ++i) {
        const dvec3 push = w * d3(warm[i]) * dtd * dtd;
        const dvec3 want = d3(x[i]) + dtd * (d3(v[i]) + dtd * (gravity + w * d3(warm[i])));
        const double e = 8.0 * u * (glm::length(d3(x[i])) + dtd * glm::length(d3(v[i])) + dtd * dtd * (g + glm::length(d3(warm[i]))));
        CHECK(vec_error(s.xstar_unsorted[i], want) <= e);
        CHECK(vec_error(s.warm_predicted[i], d3(s.xstar_unsorted[i]) - d3(x[i]) - push) <= 2.0 * e);
    }
    // The step's a^p (update_velocities.comp): (x − x_n − d)/dt² where the last lambda pass found
    // the particle compressed, capped at RANRYU_PBF_WARM_CAP |g|; 0 elsewhere. The GPU forms x − x_n − d
    // in float from numbers of size |x| ≤ 0.3 m: 4u·0.3 m, over dt².
    const double e_a = 4.0 * u * 0.3 / (dtd * dtd);
    int compressed = 0, capped = 0, free = 0;
    for (std::size_t i = 0; i < x.size(); ++i) {
        INFO("particle " << i << ", density " << s.density2[i].x);
        dvec3 want(0.0);
        if (double(s.density2[i].x) > 1000.0) {
            ++compressed;
            want = (d3(s.x2[i]) - d3(s.start[i]) - d3(s.warm_sorted[i])) / (dtd * dtd);
            if (glm::length(want) > cap) want *= cap / glm::length(want), ++capped;
        } else {
            ++free;
        }
        CHECK(vec_error(s.warm_end[i], want) <= e_a + 4.0 * u * glm::length(want));
    }
    // The block is what the test means: compressed inside, free at its faces, some accelerations capped
    // and some not.
    INFO(compressed << " compressed (" << capped << " capped), " << free << " not");
    CHECK(compressed > 64);
    CHECK(free > 0);
    CHECK(capped > 0);
    CHECK(capped < compressed);
    ranryu::test::require_no_gl_errors();
}

TEST_CASE("pbf: one whole step matches the reference step", "[pbf]") {
    ranryu::test::Random rng;
    INFO("seed " << rng.seed());
    Rig rig;
    const Stages s = random_step(rng, rig, glm::vec3(0.02f, 0.03f, 0.025f), 0.95f);
    const ref::Params p = rig.params();
    const pb::Settings set = rig.settings();
    std::vector<dvec3> xb;
    std::vector<double> psi;
    rig.boundary(xb, psi);
    // The reference from the step's start as the GPU sorted it (bit copies of the uploaded state).
    pb::State st{d3(s.start), d3(s.v0)};
    pb::step(st, xb, psi, p, set, double(s.dt), 2, gpu_rule(rig, s.xstar, s.density1));
    // The bound: each iteration's correction is off by at most its stage bound e (check_correction);
    // an error δ in the positions an iteration starts from changes its correction by at most L·δ,
    // L = |∂Δx/∂x| ≤ 1 for a projection onto the constraint (a Jacobi step moves a particle no further
    // than the violation it sees), so two iterations carry e_1·(1 + L) + e_2 ≤ 2(e_1 + e_2); on top of
    // that the prediction's 4u|x|. The velocities are the positions over dt, then XSPH: the same bound
    // over dt, and XSPH's own (c ≤ 1 keeps the smoothing a contraction).
    const std::vector<dvec3> xstar = d3(s.xstar), x1 = d3(s.x1);
    const pb::Neighbours n = ref::neighbours(xstar, p.h);
    const double e1 = check_correction("first iteration", xstar, s.x1, s.lambda1, n, xb, psi, p, set);
    const double e2 = check_correction("second iteration", x1, s.x2, s.lambda2, gpu_rule(rig, s.xstar, s.density1)(x1, n), xb, psi, p, set);
    const double e_x = 2.0 * (e1 + e2) + 4.0 * kU * 0.3;   // |x| ≤ 0.3 m in this tank
    double worst_x = 0.0, worst_v = 0.0;
    for (std::size_t i = 0; i < st.x.size(); ++i) {
        worst_x = std::max(worst_x, vec_error(s.xproj[i], st.x[i]));
        worst_v = std::max(worst_v, vec_error(s.vend[i], st.v[i]));
    }
    INFO("largest position error " << worst_x << " m (bound " << e_x << "), velocity " << worst_v << " m/s (bound " << 2.0 * e_x / double(s.dt) << ")");
    CHECK(worst_x <= e_x);
    CHECK(worst_v <= 2.0 * e_x / double(s.dt));
    ranryu::test::require_no_gl_errors();
}

TEST_CASE("pbf: a resting column settles within the stated density deviation, in the scene's substeps", "[pbf]") {
    // A column 8 x 16 x 8 particles (0.24 x 0.48 x 0.24 m at 0.03 m) filling the floor of its tank, at
    // the default 4 substeps and 4 iterations a frame, run 2 s from rest on its lattice.
    ranryu::test::SphRig rig(R"({"model": "sph", "tank": {"min": [0, 0, 0], "max": [0.24, 0.6, 0.24]},
        "sph": {"solver": "pbf"},
        "particles": {"spacing": 0.03, "blocks": [{"min": [0, 0, 0], "max": [0.24, 0.48, 0.24]}]}})",
                             "pbf_rest");
    REQUIRE(rig.fluid.count() == 1024);
    const int frames = 120;
    for (int f = 0; f < frames; ++f) rig.frame(std::uint64_t(f));
    rig.finish();
    const gpu::StepState st = rig.step();
    const float frame_dt = rig.scene.frame_dt;
    CHECK(st.frame_substeps == 4u);                                      // the scene's, every frame
    CHECK(double(st.dt) == Approx(double(frame_dt) / 4.0).epsilon(1e-5));   // (P1): the fixed step
    CHECK(double(st.time) == Approx(frames * double(frame_dt)).epsilon(1e-4));
    REQUIRE_FALSE(rig.fluid.instability());

    const std::vector<glm::vec4> xg = rig.read(rig.fluid.positions()), vg = rig.read(rig.fluid.velocities());
    const std::vector<dvec3> x = d3(xg);
    std::vector<dvec3> xb;
    std::vector<double> psi;
    rig.boundary(xb, psi);
    const gpu::SphParams& sp = rig.fluid.params();
    const ref::Params p = ref::Params::from_spacing(double(sp.spacing), double(sp.rest_density), 0.0, 0.0, dvec3(glm::vec3(sp.gravity)));
    // The densities of the final positions, computed independently of the GPU's (docs/SPH.md (2)).
    const std::vector<double> rho = ref::densities(x, xb, psi, p);
    double mean = 0.0, worst = 0.0, fastest = 0.0, mean_speed = 0.0;
    for (std::size_t i = 0; i < x.size(); ++i) {
        const double e = std::max(rho[i] / p.rest_density - 1.0, 0.0);
        mean += e / double(x.size());
        worst = std::max(worst, e);
        const double speed = double(glm::length(glm::vec3(vg[i])));
        fastest = std::max(fastest, speed);
        mean_speed += speed / double(x.size());
    }
    INFO("mean compression " << mean << ", largest " << worst << ", mean speed " << mean_speed << " m/s, fastest " << fastest << " m/s");
    // The bounds (docs/PBF.md "Accuracy and cost"). Density: the mean compression (the sweep's
    // mean_density_deviation) within 1 %, the density variation WCSPH is designed for (docs/SPH.md (3),
    // c = 10 v_max), and no particle beyond 5 %; a fixed 4 Jacobi iterations a substep cannot carry the
    // weight of 16 layers to the floor exactly, so the bottom rests compressed (measured on llvmpipe:
    // 0.57 % mean, 2.1 % largest, steady from 0.5 s on). Settled: the mean speed within 1 % of the
    // column's free-fall speed sqrt(2 g H) = 3.1 m/s, no particle beyond 5 % (measured at 2 s: 0.018
    // and 0.07 m/s; XSPH's light damping leaves a slow sloshing that halves in about a second).
    const double fall = std::sqrt(2.0 * 9.81 * 0.48);
    CHECK(mean <= 0.01);
    CHECK(worst <= 0.05);
    CHECK(mean_speed <= 0.01 * fall);
    CHECK(fastest <= 0.05 * fall);
    ranryu::test::require_no_gl_errors();
}
