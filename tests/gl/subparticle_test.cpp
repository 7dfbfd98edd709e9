// Sub-particles (engine/turbulence/subparticles.h, glsl/turbulence/subparticles/, the level set's
// splat and the drawing by level) against CPU references:
//   - levels, per-level counts and the lists of split parents equal a CPU count from the same
//     energies, exactly (the GPU compares ê with the same float thresholds), in cell order;
//   - a laminar flow makes none;
//   - every child equals spawn_subparticle() on the read-back parent, seeds and time, and siblings
//     keep their parent's mean velocity to within the noise's zero mean (a statistical bound);
//   - the budget drops the finest levels first and says so in the stats and the profile note;
//   - φ with sub-particles equals a brute-force sum in double;
//   - levels = 0 builds and runs nothing; with levels > 0 each pass runs once a frame;
//   - drawn as particles, the parents not split and the sub-particles match a CPU ray caster, with
//     the level's colour and radius r/2^E.
#include "support/gl_fixture.h"
#include "support/phong.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "frame/loop.h"
#include "frame/pipeline.h"
#include "gl/gl.h"
#include "gl/objects.h"
#include "profile/gpu_timer.h"
#include "profile/report.h"
#include "render/renderer.h"
#include "render/shading.h"
#include "scene/scene.h"
#include "shader/source.h"
#include "shared/bindings.h"
#include "sim/grid.h"
#include "sim/fluid.h"
#include "turbulence/force.h"
#include "support/sph_rig.h"
#include "surface/level_set.h"
#include "turbulence/force.h"
#include "turbulence/noise.h"
#include "support/read_pixels.h"
#include "turbulence/subparticles.h"

namespace {

namespace rt = ranryu::turbulence;
namespace gpu = ranryu::gpu;
using ranryu::gl::Buffer;

constexpr float kInf = std::numeric_limits<float>::infinity();

struct Rig {
    bool ready = (ranryu::test::context(), true);
    ranryu::shader::FileSource shaders = ranryu::shader::FileSource::embedded();
    ranryu::profile::GpuTimer timer{4, 512};
    rt::NoiseTiles tiles = rt::NoiseTiles::generate(7);
    rt::CurlNoise noise{shaders, timer, tiles};   // as TurbulenceForce holds them
};
Rig& rig() {
    static Rig r;
    return r;
}

ranryu::scene::TurbulenceSettings settings(int levels, float threshold, int budget) {
    ranryu::scene::TurbulenceSettings t;
    t.amplitude = 1e-4f;
    t.lmin = 3;
    t.lmax = 5;
    t.beta = 1.0f / 3.0f;
    t.seed = 7;
    t.coherence_time = 0.5f;
    t.subparticles.levels = levels;
    t.subparticles.threshold = threshold;
    t.subparticles.budget = budget;
    return t;
}

// Parents given directly (any order; the passes take it as the cell order), with their energies,
// seeds and a StepState holding the time.
struct Parents {
    std::vector<glm::vec4> x, v, e;
    std::vector<gpu::NoiseSeed> seeds;
    float time = 0.13f;
    Buffer bx, bv, be, bs, step;
    void upload() {
        rig();
        bx = Buffer::from<glm::vec4>(x, GL_STATIC_DRAW, "test.parents.x");
        bv = Buffer::from<glm::vec4>(v, GL_STATIC_DRAW, "test.parents.v");
        be = Buffer::from<glm::vec4>(e, GL_STATIC_DRAW, "test.parents.e");
        bs = Buffer::from<gpu::NoiseSeed>(seeds, GL_STATIC_DRAW, "test.parents.seeds");
        gpu::StepState s{};
        s.time = time;
        step = Buffer(sizeof s, GL_STATIC_DRAW, &s, "test.step");
    }
    rt::Subparticles::Inputs inputs() const { return {bx, bv, be, bs, step, x.size()}; }
};

// n parents on a jittered lattice of spacing dx with energies from `energy(i)`, seeds at random
// places (spread over `seed_extent` m, so that different parents read independent noise).
Parents make_parents(ranryu::test::Random& rng, std::size_t n, float dx, const std::function<float(std::size_t)>& energy,
                     float seed_extent = 0.0f) {
    Parents p;
    const int side = int(std::ceil(std::cbrt(double(n))));
    for (std::size_t i = 0; i < n; ++i) {
        const glm::vec3 lattice(float(i % side), float((i / side) % side), float(i / (side * side)));
        p.x.emplace_back(dx * (lattice + glm::vec3(rng.uniform(-0.1f, 0.1f), rng.uniform(-0.1f, 0.1f), rng.uniform(-0.1f, 0.1f))), 0.0f);
        p.v.emplace_back(rng.uniform(-1.0f, 1.0f), rng.uniform(-1.0f, 1.0f), rng.uniform(-1.0f, 1.0f), 0.0f);
        p.e.emplace_back(0.0f, 0.0f, 0.0f, energy(i));
        gpu::NoiseSeed s{};
        for (int k = 0; k < 2; ++k) {
            const glm::vec3 at = seed_extent > 0.0f ? glm::vec3(rng.uniform(0.0f, seed_extent), rng.uniform(0.0f, seed_extent),
                                                                rng.uniform(0.0f, seed_extent))
                                                    : glm::vec3(p.x.back());
            s.phase[k] = glm::vec4(at, rt::noise_epoch(k, p.time, 0.5f));
        }
        p.seeds.push_back(s);
    }
    p.upload();
    return p;
}

// Everything the passes wrote, read back (tests only).
struct Result {
    gpu::SubparticleState state;
    std::vector<std::uint32_t> levels, lists;
    std::vector<glm::vec4> x, v;   // the sub-particles, state.dispatch.w of them
};
Result run(rt::Subparticles& sub, const rt::Subparticles::Inputs& in, std::uint64_t frame = 0) {
    auto& timer = rig().timer;
    timer.begin_frame();
    sub.generate(in, frame);
    timer.end_frame();
    Result r;
    r.state = sub.state().read<gpu::SubparticleState>(1)[0];
    r.levels = sub.levels().read<std::uint32_t>(in.count);
    r.lists = sub.lists().read<std::uint32_t>(in.count * std::size_t(sub.levels_max()));
    r.x = sub.positions().read<glm::vec4>(r.state.dispatch.w);
    r.v = sub.velocities().read<glm::vec4>(r.state.dispatch.w);
    return r;
}

// The CPU's expectation for energies `e` (their .w): levels, lists, counts, cap, from the same thresholds.
void check_classification(const Result& r, const std::vector<glm::vec4>& e, const gpu::SubparticleParams& p) {
    const std::size_t n = e.size();
    const int levels = int(p.levels);
    std::array<std::uint64_t, 3> counts{};
    std::vector<std::vector<std::uint32_t>> lists(3);
    std::vector<int> L(n);
    for (std::size_t i = 0; i < n; ++i) {
        L[i] = rt::raw_level(e[i].w, p.level_energy, levels);
        if (L[i] > 0) {
            ++counts[std::size_t(L[i] - 1)];
            lists[std::size_t(L[i] - 1)].push_back(std::uint32_t(i));
        }
    }
    const rt::LevelCap cap = rt::choose_level_cap(counts, levels, p.budget);
    INFO("CPU counts " << counts[0] << ", " << counts[1] << ", " << counts[2] << "; cap " << cap.cap << ", total " << cap.total);
    CHECK(r.state.counts == glm::uvec4(counts[0], counts[1], counts[2], counts[0] + counts[1] + counts[2]));
    CHECK(r.state.limits.x == std::uint32_t(cap.cap));
    CHECK(r.state.limits.y == std::uint32_t(cap.finest));
    CHECK(r.state.limits.z == std::uint32_t(std::min<std::uint64_t>(cap.wanted, 0xFFFFFFFFu)));
    CHECK(r.state.limits.w == p.budget);
    CHECK(r.state.dispatch.w == cap.total);
    CHECK(r.state.draw == glm::uvec4(4u, std::uint32_t(cap.total), 0u, 0u));
    CHECK(r.state.offsets.w == (cap.cap > 0 ? counts[0] + counts[1] + counts[2] : 0u));
    std::size_t wrong_level = 0;
    for (std::size_t i = 0; i < n; ++i) {
        const std::uint32_t E = L[i] > 0 && cap.cap > 0 ? std::uint32_t(std::min(L[i], cap.cap)) : 0u;
        wrong_level += r.levels[i] != (std::uint32_t(L[i]) | (E << RANRYU_SUBPARTICLE_SPLIT_SHIFT));
    }
    CHECK(wrong_level == 0);
    for (int l = 1; l <= levels; ++l) {
        INFO("level list " << l);
        const auto begin = r.lists.begin() + std::ptrdiff_t(std::size_t(l - 1) * n);
        CHECK(std::vector<std::uint32_t>(begin, begin + std::ptrdiff_t(counts[std::size_t(l - 1)])) == lists[std::size_t(l - 1)]);
    }
}

}  // namespace

TEST_CASE("subparticles: levels follow the thresholds e_th·2^(2βk) and the log2 rule away from them", "[subparticles]") {
    // L = 0 below e_th, else min(Lmax, 1 + floor(log2(ê/e_th) / 2β)); β = 1/3: one level per factor 2^(2/3).
    const float th = 0.02f, beta = 1.0f / 3.0f;
    const glm::vec4 t = rt::level_energies(th, beta, 3);
    CHECK(t.x == th);
    CHECK(t.y == Approx(th * std::exp2(2.0 / 3.0)).epsilon(1e-6));
    CHECK(t.z == Approx(th * std::exp2(4.0 / 3.0)).epsilon(1e-6));
    CHECK(rt::level_energies(th, beta, 2).z == kInf);
    std::mt19937 rng(3);
    for (int k = 0; k < 10000; ++k) {
        const double e = th * std::exp2(std::uniform_real_distribution<double>(-3.0, 6.0)(rng));
        const double u = std::log2(e / th) / (2.0 * beta);
        if (std::abs(u - std::round(u)) < 1e-4) continue;   // too near a boundary for float
        for (int levels = 1; levels <= 3; ++levels) {
            const int want = e < th ? 0 : std::min(levels, 1 + int(std::floor(u)));
            REQUIRE(rt::raw_level(float(e), rt::level_energies(th, beta, levels), levels) == want);
        }
    }
    // β = 0: every octave has the same energy; a particle at e_th goes to the finest level.
    CHECK(rt::raw_level(th, rt::level_energies(th, 0.0f, 3), 3) == 3);
    CHECK(rt::raw_level(std::nanf(""), t, 3) == 0);
    CHECK(rt::raw_level(kInf, t, 2) == 2);
}

TEST_CASE("subparticles: σ is the exact rms of |curl| over one octave's tile", "[subparticles]") {
    // On a small tile: (1) the separable Gauss lattice equals 27 Gauss points a cell of curl_noise
    // (the CPU reference of the GPU's curl) to round-off; (2) the mean of |w|² is the continuum's: a
    // midpoint rule of m³ samples converges to it as 1/m² (measured: 0.44 %, 0.11 %, 0.03 % off the
    // rms at 8, 16, 32 samples a cell), so the Richardson extrapolation of 4 and 8 samples a cell,
    // (4·M_8 - M_4)/3, must be within 2e-4 of it.
    const rt::NoiseTiles small = rt::NoiseTiles::generate(11, 8);
    const int n = small.n;
    const double a = 0.5 * std::sqrt(0.6), offset[3] = {-a, 0.0, a}, weight[3] = {5.0 / 18.0, 8.0 / 18.0, 5.0 / 18.0};
    double gauss = 0.0;
    for (int k = 0; k < n; ++k)
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i)
                for (int c = 0; c < 27; ++c) {
                    const glm::vec3 w = rt::curl_noise(small, glm::vec3(glm::dvec3(i, j, k) + glm::dvec3(offset[c % 3], offset[c / 3 % 3], offset[c / 9])));
                    gauss += weight[c % 3] * weight[c / 3 % 3] * weight[c / 9] * glm::dot(w, w);
                }
    auto midpoint = [&](int m) {   // mean |w|² from m³ samples at cell centres of an m³ grid
        double sum = 0.0;
        for (int k = 0; k < m; ++k)
            for (int j = 0; j < m; ++j)
                for (int i = 0; i < m; ++i) {
                    const glm::vec3 w = rt::curl_noise(small, (glm::vec3(i, j, k) + 0.5f) * (float(n) / float(m)));
                    sum += glm::dot(w, w);
                }
        return sum / (double(m) * m * m);
    };
    const double rms = rt::octave_rms(small), direct = std::sqrt(gauss / (n * n * n));
    const double richardson = std::sqrt((4.0 * midpoint(8 * n) - midpoint(4 * n)) / 3.0);
    INFO("separable " << rms << ", direct Gauss " << direct << ", Richardson midpoint " << richardson);
    CHECK(rms == Approx(direct).epsilon(1e-6));
    CHECK(rms == Approx(richardson).epsilon(2e-4));
    CHECK(rt::octave_rms(rig().tiles) == Approx(1.741254).epsilon(1e-5));   // the force's tiles (seed 7): 27 points a cell, measured
}

TEST_CASE("subparticles: per-level counts, levels and the lists of split parents equal a CPU count", "[subparticles]") {
    ranryu::test::Random rng;
    INFO("seed " << rng.seed());
    // 70,000 parents: 274 classify workgroups, more than one chunk of the block scan.
    const std::size_t n = 70000;
    for (const float th : {0.01f, 0.05f}) {
        INFO("threshold " << th);
        const glm::vec4 t = rt::level_energies(th, 1.0f / 3.0f, 3);
        Parents p = make_parents(rng, n, 0.01f, [&](std::size_t i) {
            switch (i % 7) {
                case 0: return 0.0f;
                case 1: return t[int(rng.below(3))];                  // exactly at a threshold: that level
                case 2: return std::nextafter(t[int(rng.below(3))], 0.0f);   // just below it
                case 3: return i % 5 == 0 ? std::nanf("") : kInf;
                default: return th * std::exp2(rng.uniform(-3.0f, 4.0f));    // log-uniform across the levels
            }
        });
        // A budget that keeps the spawn small: most runs drop to C = 0 or 1.
        rt::Subparticles sub(rig().shaders, rig().timer, settings(3, th, 50000), 0.01f, n, rig().tiles, rig().noise);
        const Result r = run(sub, p.inputs());
        check_classification(r, p.e, sub.params());
    }
    // Every level split (a generous budget), fewer parents than one workgroup.
    Parents p = make_parents(rng, 200, 0.01f, [&](std::size_t) { return 0.01f * std::exp2(rng.uniform(-1.0f, 3.0f)); });
    rt::Subparticles sub(rig().shaders, rig().timer, settings(2, 0.01f, 1 << 20), 0.01f, 200, rig().tiles, rig().noise);
    const Result r = run(sub, p.inputs());
    check_classification(r, p.e, sub.params());
    CHECK(r.state.limits.x == 2u);
    CHECK(r.state.counts.x > 0u);
    CHECK(r.state.counts.y > 0u);
    ranryu::test::require_no_gl_errors();
}

namespace {

std::string block_json(const std::string& velocity, const std::string& gravity, const std::string& subparticles) {
    return R"({"model": "sph", "tank": {"min": [0, 0, 0], "max": [0.6, 0.3, 0.3]}, "gravity": )" + gravity + R"(,
        "sph": {"solver": "wcsph", "viscosity": 1e-3},
        "particles": {"spacing": 0.03, "blocks": [{"min": [0, 0, 0], "max": [0.6, 0.3, 0.3], "velocity": )" + velocity + R"(}]},
        "turbulence": {"amplitude": 1e-4, "scale": 0.3333333, "octaves": [3, 5], "beta": 0.3333333, "seed": 7,
                       "coherence_time": 0.5, "subparticles": )" + subparticles + "}}";
}

// The sheared flow u = u0 sin(2π y/λ) e_x, λ = 8 dx, on the block's lattice jittered by ±0.1 dx.
void upload_shear(ranryu::test::SphRig& r) {
    std::vector<glm::vec4> x = r.scene.initial_positions(), v(x.size());
    std::mt19937 rng(12345);
    std::uniform_real_distribution<float> jitter(-0.1f * r.scene.spacing, 0.1f * r.scene.spacing);
    const float lambda = 8.0f * r.scene.spacing;
    for (std::size_t i = 0; i < x.size(); ++i) {
        x[i] += glm::vec4(jitter(rng), jitter(rng), jitter(rng), 0.0f);
        v[i] = glm::vec4(0.5f * std::sin(6.2831853f * x[i].y / lambda), 0.0f, 0.0f, 0.0f);
    }
    r.fluid.upload_state(x, v);
}

rt::Subparticles make_subparticles(ranryu::test::SphRig& r) {
    return rt::Subparticles(rig().shaders, r.timer, r.scene.turbulence, r.scene.spacing, r.fluid.count(), r.sim.turbulence()->tiles(),
                            r.sim.turbulence()->noise());
}

}  // namespace

TEST_CASE("subparticles: a laminar flow (uniform, or at rest under gravity) makes none", "[subparticles]") {
    // Uniform: the block fills its tank, so the walls soon shear it; the sub-particles of the first
    // substep's analysis (ê = 0 exactly: wavelet.h) are checked, at a tiny threshold. At rest under
    // gravity: two whole frames at the default threshold, 0.01 m²/s² (the block settles under its
    // weight: measured largest ê 0.0028 m²/s² in these frames).
    for (const bool uniform : {true, false}) {
        const std::string u = uniform ? "[0.7, -0.2, 0.3]" : "[0, 0, 0]", g = uniform ? "[0, 0, 0]" : "[0, -9.81, 0]";
        const std::string sp = uniform ? R"({"levels": 3, "threshold": 1e-9, "budget": 100000})" : R"({"levels": 3})";
        INFO("velocity " << u << ", gravity " << g);
        ranryu::test::SphRig r(block_json(u, g, sp), "subparticle_test");
        rt::Subparticles sub = make_subparticles(r);
        for (std::uint64_t f = 0; f < 2; ++f) {
            r.timer.begin_frame();
            r.sim.begin_frame(f);
            if (uniform) {
                r.fluid.choose_time_step();
                r.fluid.rebuild_grid();
                r.wcsph().compute_density(r.fluid);
                r.sim.turbulence()->analyse(r.fluid);
                r.wcsph().compute_forces(r.fluid);
                r.sim.turbulence()->apply(r.fluid);   // seeds the carried noise
            } else {
                for (int s = 0; s < r.sim.substeps_this_frame(); ++s) r.sim.step();
            }
            sub.generate(r.fluid, *r.sim.turbulence(), f);
            r.sim.end_frame();
            r.timer.end_frame();
        }
        r.finish();
        sub.drain();
        const auto e = r.read(r.sim.turbulence()->wavelet().energy());
        float most = 0.0f;
        for (const auto& q : e) most = std::max(most, q.w);
        INFO("largest ê " << most);
        const gpu::SubparticleState s = sub.state().read<gpu::SubparticleState>(1)[0];
        CHECK(s.counts == glm::uvec4(0u));
        CHECK(s.dispatch.w == 0u);
        CHECK(s.draw == glm::uvec4(4u, 0u, 0u, 0u));
        for (const std::uint32_t l : sub.levels().read<std::uint32_t>(r.fluid.count())) REQUIRE(l == 0u);
        CHECK(sub.stats().frames == 2);
        CHECK(sub.stats().most == 0);
        CHECK(rt::budget_note(sub.stats()).empty());
    }
    ranryu::test::require_no_gl_errors();
}

TEST_CASE("subparticles: every child of an SPH shear flow equals the CPU reference", "[subparticles]") {
    // One substep of the shear, then the sub-particles of its state. The threshold is the median ê,
    // so about half the particles split, to levels 1 and 2.
    ranryu::test::SphRig probe(block_json("[0, 0, 0]", "[0, 0, 0]", R"({"levels": 2, "threshold": 1, "budget": 1000000})"),
                               "subparticle_test");
    upload_shear(probe);
    probe.frame(0);
    auto energies = probe.read(probe.sim.turbulence()->wavelet().energy());
    std::sort(energies.begin(), energies.end(), [](const glm::vec4& a, const glm::vec4& b) { return a.w < b.w; });
    const float median = energies[energies.size() / 2].w;
    REQUIRE(median > 0.0f);
    char sp[160];
    std::snprintf(sp, sizeof sp, R"({"levels": 2, "threshold": %.9g, "budget": 1000000})", double(median));

    ranryu::test::SphRig r(block_json("[0, 0, 0]", "[0, 0, 0]", sp), "subparticle_test");
    upload_shear(r);
    rt::Subparticles sub = make_subparticles(r);
    r.timer.begin_frame();
    r.sim.begin_frame(0);
    for (int s = 0; s < r.sim.substeps_this_frame(); ++s) r.sim.step();
    sub.generate(r.fluid, *r.sim.turbulence(), 0);
    r.sim.end_frame();
    r.timer.end_frame();
    r.finish();
    const std::size_t n = r.fluid.count();
    const auto x = r.read(r.fluid.positions()), v = r.read(r.fluid.velocities()), e = r.read(r.sim.turbulence()->wavelet().energy());
    const auto seeds = r.sim.turbulence()->noise_seeds().read<gpu::NoiseSeed>(n);
    const float t = r.step().time;
    const gpu::SubparticleState s = sub.state().read<gpu::SubparticleState>(1)[0];
    const auto lists = sub.lists().read<std::uint32_t>(2 * n);
    const auto cx = sub.positions().read<glm::vec4>(s.dispatch.w), cv = sub.velocities().read<glm::vec4>(s.dispatch.w);
    INFO("t = " << t << " s; counts " << s.counts.x << ", " << s.counts.y << "; " << s.dispatch.w << " sub-particles");
    REQUIRE(s.limits.x == 2u);
    REQUIRE(s.counts.x > 50u);
    REQUIRE(s.counts.y > 50u);
    REQUIRE(s.dispatch.w == s.counts.x * 8u + s.counts.y * 64u);

    // Tolerance: the noise's float evaluation (a few ulp of |y|·2^octave in the coordinates) and
    // the sums; relative 1e-4 of the child's offset and velocity kick, plus ulps of |x_p|, |v_p|.
    std::size_t bad = 0, checked = 0;
    double worst_x = 0.0, worst_v = 0.0;
    for (std::uint32_t g = 0; g < s.dispatch.w; ++g) {
        const int L = g >= s.offsets.y ? 2 : 1;
        const std::uint32_t local = g - (L == 2 ? s.offsets.y : 0u), k = local >> (3 * L), c = local & ((1u << (3 * L)) - 1u);
        const std::uint32_t p = lists[std::size_t(L - 1) * n + k];
        const rt::Subparticle want =
            rt::spawn_subparticle(r.sim.turbulence()->tiles(), sub.params(), glm::vec3(x[p]), glm::vec3(v[p]), e[p].w, seeds[p], c, L, t);
        const double kick = std::sqrt(2.0 * want.velocity.w);
        const double dx = glm::length(glm::dvec3(cx[g]) - glm::dvec3(want.position));
        const double dv = glm::length(glm::dvec3(cv[g]) - glm::dvec3(want.velocity));
        const double tol_x = 1e-4 * r.scene.spacing + 4e-7 * glm::length(glm::vec3(x[p]));
        const double tol_v = 1e-4 * kick + 4e-7 * glm::length(glm::vec3(v[p]));
        worst_x = std::max(worst_x, dx / tol_x);
        worst_v = std::max(worst_v, dv / tol_v);
        const bool ok = dx <= tol_x && dv <= tol_v && cx[g].w == want.position.w &&
                        std::abs(cv[g].w - want.velocity.w) <= 1e-6f * want.velocity.w;
        if (!ok && ++bad <= 5)
            FAIL_CHECK("sub-particle " << g << " (parent " << p << ", level " << L << ", child " << c << "): GPU x ("
                                       << cx[g].x << ", " << cx[g].y << ", " << cx[g].z << ", " << cx[g].w << ") v (" << cv[g].x
                                       << ", " << cv[g].y << ", " << cv[g].z << ", " << cv[g].w << "), CPU x (" << want.position.x
                                       << ", " << want.position.y << ", " << want.position.z << ") v (" << want.velocity.x << ", "
                                       << want.velocity.y << ", " << want.velocity.z << ", " << want.velocity.w << ")");
        ++checked;
    }
    INFO("worst error / tolerance: position " << worst_x << ", velocity " << worst_v);
    CHECK(bad == 0);
    CHECK(checked == s.dispatch.w);
    ranryu::test::require_no_gl_errors();
}

TEST_CASE("subparticles: siblings keep their parent's mean velocity to within the noise's zero mean", "[subparticles]") {
    // P parents whose seeds lie far apart (independent noise), at levels 1 and 2. For each parent,
    // m_p = mean over its 8^E children of (v_c - v_p)/√(2 e_E) = the mean of their ŷ_c. The curl
    // noise has zero mean (the curl of a periodic field), so the m_p are independent samples of mean
    // 0 and, per component, variance at most 1/3 (ŷ has unit rms, isotropic: 1/3 a component; the
    // bound is reached when siblings are fully correlated). Their grand mean M must then satisfy
    // |M_a| < 5·√(1/(3P)) (5 standard deviations at the worst correlation: a false alarm about once
    // in 10^6 runs per component). Also checked: mean |ŷ|² over all children ≈ 1 (σ is right).
    ranryu::test::Random rng;
    INFO("seed " << rng.seed());
    const std::size_t P = 3000;
    const float th = 0.01f;
    const glm::vec4 t = rt::level_energies(th, 1.0f / 3.0f, 2);
    Parents p = make_parents(rng, P, 0.02f, [&](std::size_t i) { return (i % 2 ? t.y : t.x) * rng.uniform(1.0f, 1.5f); }, 40.0f);
    rt::Subparticles sub(rig().shaders, rig().timer, settings(2, th, 1 << 20), 0.02f, P, rig().tiles, rig().noise);
    const Result r = run(sub, p.inputs());
    REQUIRE(r.state.limits.x == 2u);
    REQUIRE(r.state.dispatch.w == (P / 2) * 8 + (P / 2) * 64);
    glm::dvec3 grand(0.0), grand_sq(0.0);
    double norm2 = 0.0;
    std::size_t children = 0;
    for (std::uint32_t g = 0; g < r.state.dispatch.w;) {
        const int L = g >= r.state.offsets.y ? 2 : 1;
        const std::uint32_t siblings = 1u << (3 * L);
        const std::uint32_t parent = r.lists[std::size_t(L - 1) * P + ((g - (L == 2 ? r.state.offsets.y : 0u)) >> (3 * L))];
        glm::dvec3 m(0.0);
        for (std::uint32_t c = 0; c < siblings; ++c, ++g) {
            const glm::dvec3 y = (glm::dvec3(r.v[g]) - glm::dvec3(p.v[parent])) / std::sqrt(2.0 * double(r.v[g].w));
            m += y;
            norm2 += glm::dot(y, y);
            ++children;
        }
        m /= double(siblings);
        grand += m;
        grand_sq += m * m;
    }
    grand /= double(P);
    const glm::dvec3 sd = glm::sqrt(grand_sq / double(P) - grand * grand);
    const double bound = 5.0 * std::sqrt(1.0 / (3.0 * double(P)));
    INFO("mean of sibling means " << grand.x << ", " << grand.y << ", " << grand.z << " (bound " << bound
                                  << "); their sd " << sd.x << ", " << sd.y << ", " << sd.z << "; mean |ŷ|² "
                                  << norm2 / double(children));
    for (int a = 0; a < 3; ++a) {
        CHECK(std::abs(grand[a]) < bound);
        CHECK(sd[a] < std::sqrt(1.0 / 3.0) * 1.2);   // the variance bound the test relies on holds
    }
    CHECK(norm2 / double(children) == Approx(1.0).margin(0.15));
    ranryu::test::require_no_gl_errors();
}

TEST_CASE("subparticles: a small budget drops the finest levels first, and the stats and note say so", "[subparticles]") {
    ranryu::test::Random rng;
    INFO("seed " << rng.seed());
    // n = (100, 50, 20) at levels 1, 2, 3 among 1000 parents: need(3) = 14240, need(2) = 5280, need(1) = 1360.
    const float th = 0.01f;
    const glm::vec4 t = rt::level_energies(th, 1.0f / 3.0f, 3);
    Parents p = make_parents(rng, 1000, 0.01f, [&](std::size_t i) {
        const std::size_t k = (i * 7919) % 1000;   // scattered
        return k < 100 ? t.x : k < 150 ? t.y * 1.01f : k < 170 ? t.z * 3.0f : 0.5f * th;
    });
    struct Case {
        int budget, cap;
        std::uint32_t total;
    };
    for (const Case c : {Case{20000, 3, 14240}, Case{14239, 2, 5280}, Case{6000, 2, 5280}, Case{1360, 1, 1360}, Case{1359, 0, 0}}) {
        INFO("budget " << c.budget);
        rt::Subparticles sub(rig().shaders, rig().timer, settings(3, th, c.budget), 0.01f, 1000, rig().tiles, rig().noise);
        for (std::uint64_t f = 0; f < 3; ++f) run(sub, p.inputs(), f);
        const Result r = run(sub, p.inputs(), 3);
        check_classification(r, p.e, sub.params());
        CHECK(r.state.counts == glm::uvec4(100u, 50u, 20u, 170u));
        CHECK(r.state.limits.x == std::uint32_t(c.cap));
        CHECK(r.state.dispatch.w == c.total);
        CHECK(r.state.dispatch.w <= std::uint32_t(c.budget));
        std::array<std::uint32_t, 4> by_level{};
        for (const glm::vec4& q : r.x) ++by_level[std::size_t(q.w)];
        // Level-L parents have 8^min(L, C) children of level min(L, C): nothing finer than C.
        std::array<std::uint32_t, 4> want{};
        const std::uint32_t n_L[3] = {100u, 50u, 20u};
        for (int L = 1; L <= 3 && c.cap > 0; ++L) want[std::size_t(std::min(L, c.cap))] += n_L[L - 1] << (3 * std::min(L, c.cap));
        CHECK(by_level == want);
        // The stats came back asynchronously; the note names the budget and the level kept.
        sub.drain();
        const rt::SubparticleStats& st = sub.stats();
        CHECK(st.frames == 4);
        CHECK(st.budget == std::uint32_t(c.budget));
        const std::string note = rt::budget_note(st);
        INFO("note: " << note);
        if (c.cap == 3) {
            CHECK(st.dropped_frames == 0);
            CHECK(note.empty());
        } else {
            CHECK(st.dropped_frames == 4);
            CHECK(st.lowest_cap == c.cap);
            CHECK(st.finest_wanted == 3);
            CHECK(note == "sub-particles: budget " + std::to_string(c.budget) + " exceeded in 4 of 4 frames, finest level dropped to " +
                              std::to_string(c.cap) + " (levels up to 3 wanted)");
        }
        sub.count_from(10);   // e.g. after warm-up: earlier frames' records no longer count
        run(sub, p.inputs(), 9);
        sub.drain();
        CHECK(sub.stats().frames == 0);
    }
    ranryu::test::require_no_gl_errors();
}

namespace {

// Parents sorted into cell order by a neighbour grid, as the SPH leaves them for the level set.
struct SortedParents {
    ranryu::sim::NeighbourGrid grid;
    ranryu::sim::CellRanges ranges;
    Buffer sorted_x, sorted_v;
    std::vector<glm::vec4> x;   // in cell order
    SortedParents(const std::vector<glm::vec4>& raw, glm::vec3 lo, glm::vec3 hi, float cell)
        : grid(rig().shaders, rig().timer, ranryu::sim::GridLayout::covering(lo, hi, cell, false), raw.size(),
               ranryu::sim::SortMethod::radix),
          ranges(grid.make_ranges("test.cells")),
          sorted_x(raw.size() * sizeof(glm::vec4), GL_DYNAMIC_COPY, nullptr, "test.sorted_x"),
          sorted_v(raw.size() * sizeof(glm::vec4), GL_DYNAMIC_COPY, nullptr, "test.sorted_v") {
        const Buffer bx = Buffer::from<glm::vec4>(raw, GL_STATIC_DRAW, "test.raw_x");
        const std::vector<glm::vec4> zero(raw.size(), glm::vec4(0.0f));
        const Buffer bv = Buffer::from<glm::vec4>(zero, GL_STATIC_DRAW, "test.raw_v");
        rig().timer.begin_frame();
        grid.build(bx, bv, sorted_x, sorted_v, ranges, raw.size(), /*clear=*/true);
        rig().timer.end_frame();
        x = sorted_x.read<glm::vec4>(raw.size());
    }
};

}  // namespace

TEST_CASE("subparticles: the level set with sub-particles equals a brute-force sum in double", "[subparticles]") {
    ranryu::test::Random rng;
    INFO("seed " << rng.seed());
    const float dx = 0.02f;
    // A 5x4x5 block of jittered lattice and a few drops above it; ê chosen per cell-ordered parent below.
    std::vector<glm::vec4> raw;
    const glm::vec3 corner(0.14f, 0.13f, 0.15f);
    for (int k = 0; k < 5; ++k)
        for (int j = 0; j < 4; ++j)
            for (int i = 0; i < 5; ++i)
                raw.emplace_back(corner + dx * (glm::vec3(i, j, k) + glm::vec3(rng.uniform(-0.2f, 0.2f), rng.uniform(-0.2f, 0.2f),
                                                                               rng.uniform(-0.2f, 0.2f))),
                                 0.0f);
    for (int d = 0; d < 3; ++d) raw.emplace_back(corner + glm::vec3(rng.uniform(0.0f, 0.08f), rng.uniform(0.1f, 0.12f), rng.uniform(0.0f, 0.08f)), 0.0f);
    SortedParents sorted(raw, glm::vec3(0.08f), glm::vec3(0.4f), 2.0f * dx);
    const std::size_t n = raw.size();

    const float th = 0.01f;
    const glm::vec4 t = rt::level_energies(th, 1.0f / 3.0f, 2);
    Parents p;
    p.x = sorted.x;
    for (std::size_t i = 0; i < n; ++i) {
        const unsigned pick = rng.below(3);   // a third each: not split, level 1, level 2
        p.e.emplace_back(0.0f, 0.0f, 0.0f, pick == 0 ? 0.0f : pick == 1 ? t.x : t.y * 1.2f);
        p.v.emplace_back(0.0f);
        gpu::NoiseSeed s{};
        for (int k = 0; k < 2; ++k) s.phase[k] = glm::vec4(glm::vec3(p.x[i]), rt::noise_epoch(k, p.time, 0.5f));
        p.seeds.push_back(s);
    }
    p.upload();
    const auto cfg = settings(2, th, 1 << 20);
    rt::Subparticles sub(rig().shaders, rig().timer, cfg, dx, n, rig().tiles, rig().noise);

    for (const float node : {0.5f, 0.125f}) {   // nodes dx/2 (R_E floored at 0.75 dx) and dx/8 (R_E = R/2^E)
        INFO("node spacing " << node << " dx");
        auto s = ranryu::surface::LevelSetSettings::for_spacing(dx);
        s.node_spacing = node * dx;
        s.max_dims = glm::uvec3(72u);
        s.subparticle_levels = 2;
        ranryu::surface::LevelSet ls(rig().shaders, rig().timer, s);
        const ranryu::surface::SubparticleSurface with{sub.levels(), sub.positions(), sub.state(), rt::Subparticles::dispatch_offset,
                                                        sub.dispatch_group()};
        std::vector<float> first;
        for (int pass = 0; pass < 2; ++pass) {   // twice: the splat grid is back to 0 after each frame
            auto& timer = rig().timer;
            timer.begin_frame();
            sub.generate(p.inputs(), 0);
            ls.compute(sorted.grid, sorted.sorted_x, sorted.ranges, n, &with);
            timer.end_frame();
            const gpu::SurfaceGrid sg = ls.grid().read<gpu::SurfaceGrid>(1)[0];
            REQUIRE(sg.dims.w > 0u);
            const std::vector<float> phi = ls.phi().read<float>(sg.dims.w);
            if (pass == 1) {
                CHECK(phi == first);
                break;
            }
            first = phi;
            const gpu::SubparticleState st = sub.state().read<gpu::SubparticleState>(1)[0];
            const auto levels = sub.levels().read<std::uint32_t>(n);
            const auto children = sub.positions().read<glm::vec4>(st.dispatch.w);
            REQUIRE(st.limits.x == 2u);
            REQUIRE(children.size() > 200u);
            ranryu::surface::PhiGrid g{glm::vec3(sg.origin), sg.origin.w, glm::uvec3(sg.dims), {}};
            INFO("grid " << g.dims.x << "x" << g.dims.y << "x" << g.dims.z << " at " << g.spacing << " m; " << children.size()
                         << " sub-particles");
            // The grid holds every child's support (the margin covers them).
            for (const glm::vec4& c : children) {
                const float R = ranryu::surface::subparticle_kernel_radius(s.kernel_radius, int(c.w), g.spacing);
                REQUIRE(glm::all(glm::greaterThanEqual(glm::vec3(c) - R, g.origin)));
                REQUIRE(glm::all(glm::lessThanEqual(glm::vec3(c) + R, g.node(g.dims - 1u))));
            }
            ranryu::surface::level_set_cpu(sorted.x, levels, children, s, g);
            // Tolerance: the float gather's (surface_test.cpp: 1e-5 of the sum and of the peak V·W(0))
            // plus the fixed point's rounding, at most 2^-25 for each of the children (bounded by all of them).
            const double peak = double(dx) * dx * dx * ranryu::surface::kernel_w(0.0, s.kernel_radius);
            const double quantum = std::ldexp(1.0, -25) * double(children.size());
            std::size_t bad = 0;
            double worst = 0.0;
            for (std::size_t i = 0; i < phi.size(); ++i) {
                const double c = double(g.phi[i]) + s.iso, err = std::abs(double(phi[i]) - double(g.phi[i]));
                const double tol = 1e-5 * std::abs(c) + 1e-5 * peak + std::min(quantum, 1e-5);
                worst = std::max(worst, err / tol);
                bad += err > tol;
            }
            INFO(bad << " of " << phi.size() << " nodes off; worst error / tolerance " << worst);
            CHECK(bad == 0);
            // Volume: Σ (φ + iso)·h³ over the grid is the parents' and children's volume, V each or V/8^E.
            double volume = 0.0;
            for (const float f : phi) volume += (double(f) + s.iso) * double(g.spacing) * g.spacing * g.spacing;
            double want = 0.0;
            for (const std::uint32_t l : levels) want += (l >> RANRYU_SUBPARTICLE_SPLIT_SHIFT) ? 0.0 : 1.0;
            for (const glm::vec4& c : children) want += std::ldexp(1.0, -3 * int(c.w));
            want *= double(dx) * dx * dx;
            CHECK(volume == Approx(want).epsilon(0.02));   // the node sum of a sampled kernel (R >= 1.5 h)
        }
    }
    ranryu::test::require_no_gl_errors();
}

namespace {

std::string small_scene(int levels) {
    return R"({"name": "sub-small", "model": "sph", "tank": {"min": [0, 0, 0], "max": [0.3, 0.3, 0.2]}, "gravity": [0, -9.81, 0],
        "time": {"frame_dt": 0.005},
        "particles": {"spacing": 0.03, "blocks": [{"min": [0, 0, 0], "max": [0.24, 0.15, 0.18], "velocity": [1.0, 0, 0]}]},
        "turbulence": {"amplitude": 1e-4, "octaves": [3, 5], "subparticles": {"levels": )" +
           std::to_string(levels) + R"(, "threshold": 1e-6, "budget": 20000}},
        "camera": {"eye": [0.6, 0.5, 0.7], "target": [0.15, 0.08, 0.1], "fov_deg": 40}})";
}

const ranryu::profile::PassSamples* find_pass(const ranryu::profile::GpuTimer& t, const std::string& name) {
    for (const auto& p : t.passes())
        if (p.name == name) return &p;
    return nullptr;
}

}  // namespace

TEST_CASE("subparticles: levels 0 builds and runs nothing, levels above 0 run each pass once a frame", "[subparticles]") {
    ranryu::test::context();
    const char* names[] = {"subparticles.classify", "subparticles.scan", "subparticles.compact", "subparticles.budget",
                           "subparticles.spawn", "subparticles.splat"};
    for (const auto shading : {ranryu::render::Shading::fresnel, ranryu::render::Shading::particles}) {
        INFO("shading " << ranryu::render::shading_name(shading));
        {
            const auto scene = ranryu::scene::parse(small_scene(0), "subparticle_test");
            REQUIRE(scene.turbulence.enabled());
            ranryu::frame::Pipeline pipeline(scene, rig().shaders, 48, 32, shading);
            CHECK(pipeline.subparticles() == nullptr);
            for (int f = 0; f < 2; ++f) {
                pipeline.begin_frame();
                pipeline.simulate();
                pipeline.draw();
                pipeline.end_frame();
            }
            pipeline.drain();
            for (const char* name : names) CHECK(find_pass(pipeline.timer(), name) == nullptr);   // not even named
            CHECK(find_pass(pipeline.timer(), "wavelet") != nullptr);
        }
        const auto scene = ranryu::scene::parse(small_scene(2), "subparticle_test");
        ranryu::frame::Pipeline pipeline(scene, rig().shaders, 48, 32, shading);
        REQUIRE(pipeline.subparticles() != nullptr);
        REQUIRE(ranryu::frame::run_frames(pipeline, 3) == 3);
        pipeline.drain();
        CHECK(!pipeline.instability());
        const bool surface = shading != ranryu::render::Shading::particles;
        for (const char* name : names) {
            INFO("pass " << name);
            const auto* p = find_pass(pipeline.timer(), name);
            if (std::string(name) == "subparticles.splat" && !surface) {
                CHECK(p == nullptr);
                continue;
            }
            REQUIRE(p != nullptr);
            CHECK(p->calls == std::vector<int>(3, 1));
        }
        // The stats came back for every frame, and sub-particles were made (e_th is tiny).
        const rt::SubparticleStats& st = pipeline.subparticles()->stats();
        CHECK(st.frames == 3);
        CHECK(st.most > 0);
    }
    ranryu::test::require_no_gl_errors();
}

namespace {

constexpr int kW = 160, kH = 120;

// A ray caster for spheres against the clear colour (as tests/gl/render_test.cpp's), shading as
// glsl/common/frame.glsl does.
struct Caster {
    const gpu::FrameParams& f;
    glm::dmat4 inv = glm::inverse(glm::dmat4(f.view_proj));
    glm::dvec3 eye() const { return glm::dvec3(f.eye); }
    glm::dvec3 ray(double x, double y) const {
        const glm::dvec2 ndc(2.0 * x / kW - 1.0, 2.0 * y / kH - 1.0);
        const glm::dvec4 a = inv * glm::dvec4(ndc, -1.0, 1.0), b = inv * glm::dvec4(ndc, 1.0, 1.0);
        return glm::normalize(glm::dvec3(b) / b.w - glm::dvec3(a) / a.w);
    }
    glm::dvec2 window(glm::dvec3 p) const {
        const glm::dvec4 c = glm::dmat4(f.view_proj) * glm::dvec4(p, 1.0);
        return {(0.5 * c.x / c.w + 0.5) * kW, (0.5 * c.y / c.w + 0.5) * kH};
    }
    glm::dvec3 shade(glm::dvec3 base, glm::dvec3 n, glm::dvec3 v) const { return ranryu::test::phong(f, base, n, v); }
};

struct Ball {
    glm::dvec3 centre;
    double radius;
    glm::dvec3 base;
};

}  // namespace

TEST_CASE("subparticles: drawn as particles, unsplit parents and sub-particles show their level's colour and radius",
          "[subparticles]") {
    // Parents: A (not split) and B (split: its levels word has E = 1, so it is not drawn). Sub-particles
    // of levels 1, 2 and 3 elsewhere, and one of level 3 in front of A. The camera looks up at them, so behind them is the clear colour.
    // Both rasters of the impostors (docs/RENDERING.md (R15)): the draw, and the compute raster from
    // the spawn pass's dispatch.
    ranryu::test::context();
    ranryu::scene::Scene sc;
    sc.tank_min = glm::vec3(0.0f);
    sc.tank_max = glm::vec3(1.0f);
    sc.particle_radius = 0.3f;
    sc.light_dir = glm::vec3(0.3f, 1.0f, 0.8f);
    sc.ambient = 0.25f;
    const ranryu::render::Camera cam{glm::vec3(0.5f, 2.0f, 3.0f), glm::vec3(0.5f, 3.0f, 0.5f), 40.0f};
    const gpu::FrameParams fp = ranryu::render::frame_params(sc, cam, kW, kH);
    const Caster cast{fp};
    const glm::dvec3 centre(0.5, 2.9, 0.7);
    const glm::dvec3 right = glm::dvec3(glm::transpose(glm::dmat3(glm::dmat4(fp.view)))[0]);   // camera x in world
    const glm::dvec3 levels_rgb[4] = {{RANRYU_LEVEL_COLOR_0}, {RANRYU_LEVEL_COLOR_1}, {RANRYU_LEVEL_COLOR_2}, {RANRYU_LEVEL_COLOR_3}};
    const double r = sc.particle_radius;
    const glm::dvec3 a = centre - 0.85 * right, b = centre - 0.2 * right;
    // And a fourth sub-particle, of level 3, 0.45 m in front of A's centre towards the eye and a little to
    // its side: on A's disc, where a sphere drawn at another radius than its level's would show.
    const glm::dvec3 front = a + 0.45 * glm::normalize(cast.eye() - a) + 0.12 * right;
    const std::vector<Ball> drawn = {{a, r, levels_rgb[0]},
                                     {centre + 0.25 * right, r / 2, levels_rgb[1]},
                                     {centre + 0.6 * right, r / 4, levels_rgb[2]},
                                     {centre + 0.85 * right, r / 8, levels_rgb[3]},
                                     {front, r / 8, levels_rgb[3]}};
    const std::vector<glm::vec4> parents = {glm::vec4(glm::vec3(a), 0.0f), glm::vec4(glm::vec3(b), 0.0f)};
    const std::vector<std::uint32_t> words = {0u, 1u | (1u << RANRYU_SUBPARTICLE_SPLIT_SHIFT)};
    std::vector<glm::vec4> children;
    for (int k = 1; k <= 3; ++k) children.emplace_back(glm::vec3(drawn[std::size_t(k)].centre), float(k));
    children.emplace_back(glm::vec3(front), 3.0f);
    const std::vector<glm::vec4> still(4, glm::vec4(0.0f));
    gpu::SubparticleState state{};
    state.draw = glm::uvec4(4u, 4u, 0u, 0u);
    // The spawn pass's dispatch as the compute raster reads it: two sub-particles a workgroup, in two
    // rows of one workgroup (surface/dispatch_2d.glsl), the draw's arguments after it.
    state.dispatch = glm::uvec4(1u, 2u, 1u, 4u);

    const Buffer px = Buffer::from<glm::vec4>(parents, GL_STATIC_DRAW, "test.parents");
    const Buffer pv(2 * sizeof(glm::vec4), GL_STATIC_DRAW, still.data(), "test.parents_v");
    const Buffer pl = Buffer::from<std::uint32_t>(words, GL_STATIC_DRAW, "test.levels");
    const Buffer cx = Buffer::from<glm::vec4>(children, GL_STATIC_DRAW, "test.children");
    const Buffer cv(4 * sizeof(glm::vec4), GL_STATIC_DRAW, still.data(), "test.children_v");
    const Buffer st(sizeof state, GL_STATIC_DRAW, &state, "test.state");
    for (const auto raster : {ranryu::render::ImpostorOptions::Raster::draw, ranryu::render::ImpostorOptions::Raster::compute}) {
    const bool compute = raster == ranryu::render::ImpostorOptions::Raster::compute;
    INFO("impostors: " << (compute ? "compute" : "draw"));
    ranryu::profile::GpuTimer timer;
    ranryu::render::ImpostorOptions options;
    options.raster = raster;
    ranryu::render::Renderer renderer(rig().shaders, timer, ranryu::render::Shading::particles, true, false, {}, options);
    renderer.set_frame(fp);
    renderer.resize(kW, kH);
    ranryu::gl::RenderTarget target(kW, kH, "subparticle_test");
    const ranryu::render::SubparticleDraw sub{pl, cx, cv, st, offsetof(gpu::SubparticleState, draw),
                                              offsetof(gpu::SubparticleState, dispatch), compute ? 2u : 0u};
    timer.begin_frame();
    renderer.draw(target, px, pv, 2, nullptr, &sub);
    timer.end_frame();
    const std::vector<std::uint8_t> rgba = ranryu::test::read_rgba(target);
    timer.drain();
    // Every pixel clear of a silhouette (closest approach within 5 % of a radius), to 3/255.
    const glm::dvec3 clear = 255.0 * glm::dvec3(0.16, 0.18, 0.22);
    std::array<int, 5> seen{};
    int failures = 0, background = 0, under_b = 0;
    const glm::dvec2 b_px = cast.window(b);
    for (int j = 0; j < kH; ++j)
        for (int i = 0; i < kW; ++i) {
            const glm::dvec3 dir = cast.ray(i + 0.5, j + 0.5);
            int hit = -1;
            double t_hit = 1e30;
            bool edge = false;
            for (std::size_t k = 0; k < drawn.size(); ++k) {
                const glm::dvec3 oc = drawn[k].centre - cast.eye();
                const double bb = glm::dot(dir, oc), d2 = glm::dot(oc, oc) - bb * bb;
                const double approach = std::sqrt(std::max(d2, 0.0)) / drawn[k].radius;
                if (approach > 0.95 && approach < 1.05) edge = true;
                if (approach < 1.0 && bb - std::sqrt(drawn[k].radius * drawn[k].radius - d2) < t_hit) {
                    t_hit = bb - std::sqrt(drawn[k].radius * drawn[k].radius - d2);
                    hit = int(k);
                }
            }
            if (edge) continue;
            glm::dvec3 want = clear;
            if (hit >= 0) {
                const glm::dvec3 q = cast.eye() + t_hit * dir;
                want = cast.shade(drawn[std::size_t(hit)].base, (q - drawn[std::size_t(hit)].centre) / drawn[std::size_t(hit)].radius, -dir);
                ++seen[std::size_t(hit)];
            } else {
                ++background;
                under_b += glm::length(glm::dvec2(i + 0.5, j + 0.5) - b_px) < 3.0;
            }
            const std::size_t o = 4 * (std::size_t(j) * kW + std::size_t(i));
            const glm::dvec3 got(rgba[o], rgba[o + 1], rgba[o + 2]);
            const double err = std::max({std::abs(got.r - want.r), std::abs(got.g - want.g), std::abs(got.b - want.b)});
            if (err > 3.0 && ++failures <= 8)
                FAIL_CHECK("pixel (" << i << ", " << j << ") " << (hit >= 0 ? "level sphere " + std::to_string(hit) : "background")
                                     << ": GPU (" << got.r << ", " << got.g << ", " << got.b << "), CPU (" << want.r << ", " << want.g
                                     << ", " << want.b << ")");
        }
    INFO("pixels compared: level 0: " << seen[0] << ", 1: " << seen[1] << ", 2: " << seen[2] << ", 3: " << seen[3]
                                      << ", 3 in front of A: " << seen[4] << ", background " << background << " (" << under_b
                                      << " where parent B would be)");
    CHECK(failures == 0);
    for (int k = 0; k < 5; ++k) CHECK(seen[std::size_t(k)] > 0);   // every level drawn, at its radius (the edges are left out)
    CHECK(under_b > 0);                                            // the split parent is not drawn
    }
    ranryu::test::require_no_gl_errors();
}

// Benchmark, not a test (hidden: `ranryu_gl_tests "[subparticle-bench]"` on the GPU host). N parents
// (RANRYU_SUB_BENCH_N, default 1,048,576) on a cubic lattice, sorted into cell order, with synthetic
// energies that make 10 %, 50 % and 100 % of them energetic, half at level 1 and half at level 2
// (L_max = 2; at 100 %: about 524k parents a level, 37.7M sub-particles; the buffers hold
// N·64 = 67M, 2.1 GB); 20 frames after 3 of warm-up, each: the sub-particle passes and the level set
// with them (the default level set settings: nodes dx/2 apart, 160³ at most).
// Prints the per-pass table of profile::summarize (classify, budget, spawn, splat, and the level
// set's own passes for comparison).
TEST_CASE("subparticles: benchmark", "[.][subparticle-bench]") {
    const char* env = std::getenv("RANRYU_SUB_BENCH_N");
    const std::size_t n = env ? std::size_t(std::strtoull(env, nullptr, 10)) : std::size_t(1) << 20;
    const int side = int(std::ceil(std::cbrt(double(n))));
    const float dx = 1.0f / float(side), th = 0.01f;
    std::vector<glm::vec4> raw(n);
    for (std::size_t i = 0; i < n; ++i)
        raw[i] = glm::vec4(dx * (glm::vec3(float(i % side), float((i / side) % side), float(i / (std::size_t(side) * side))) + 0.5f), 0.0f);
    SortedParents sorted(raw, glm::vec3(-0.1f), glm::vec3(1.1f), 2.0f * dx);
    const glm::vec4 t = rt::level_energies(th, 1.0f / 3.0f, 2);
    Parents p;
    p.x = sorted.x;
    p.v.assign(n, glm::vec4(0.1f, 0.0f, 0.0f, 0.0f));
    p.seeds.assign(n, rt::unseeded_noise());
    for (std::size_t i = 0; i < n; ++i)
        for (int k = 0; k < 2; ++k) p.seeds[i].phase[k] = glm::vec4(glm::vec3(p.x[i]), rt::noise_epoch(k, p.time, 0.5f));
    p.e.assign(n, glm::vec4(0.0f));
    p.upload();
    auto s = ranryu::surface::LevelSetSettings::for_spacing(dx);
    s.subparticle_levels = 2;
    const auto& info = ranryu::test::context().info();
    for (const int percent : {10, 50, 100}) {
        for (std::size_t i = 0; i < n; ++i) {
            const std::size_t h = (i * 2654435761u) % 100;   // a scattered `percent` % of the particles
            p.e[i].w = h < std::size_t(percent) ? (h % 2 ? t.y * 1.1f : t.x * 1.1f) : 0.0f;
        }
        p.be.upload(p.e.data(), n * sizeof(glm::vec4));
        ranryu::profile::GpuTimer timer(4, 64);
        rt::Subparticles sub(rig().shaders, timer, settings(2, th, 1 << 28), dx, n, rig().tiles, rig().noise);
        ranryu::surface::LevelSet ls(rig().shaders, timer, s);
        const ranryu::surface::SubparticleSurface with{sub.levels(), sub.positions(), sub.state(), rt::Subparticles::dispatch_offset,
                                                        sub.dispatch_group()};
        for (int f = 0; f < 23; ++f) {
            if (f == 3) {
                timer.drain();
                timer.reset_samples();
            }
            timer.begin_frame();
            sub.generate(p.inputs(), std::uint64_t(f));
            ls.compute(sorted.grid, sorted.sorted_x, sorted.ranges, n, &with);
            timer.end_frame();
        }
        timer.drain();
        sub.drain();
        const gpu::SubparticleState st = sub.state().read<gpu::SubparticleState>(1)[0];
        ranryu::profile::RunInfo run;
        run.renderer = info.renderer;
        run.driver = info.version;
        run.platform = info.platform;
        run.scene = "sub-particles, " + std::to_string(n) + " parents, " + std::to_string(percent) + " % energetic (levels 1: " +
                    std::to_string(st.counts.x) + ", 2: " + std::to_string(st.counts.y) + "), " + std::to_string(st.dispatch.w) +
                    " sub-particles";
        run.particles = n;
        run.frames = 20;
        run.warmup = 3;
        std::printf("%s\n%s\n", run.scene.c_str(), ranryu::profile::table(ranryu::profile::summarize(timer, run)).c_str());
        CHECK(st.limits.x == 2u);
    }
    ranryu::test::require_no_gl_errors();
}

TEST_CASE("subparticles: a pipeline's sub-particles drawn by the impostors' compute raster match the draw's", "[subparticles]") {
    // The pipeline's own SubparticleDraw (the spawn pass's dispatch and draw arguments, read where the
    // pipeline says they are) through both rasters (docs/RENDERING.md (R15)), on the same simulation:
    // the same pixels but where a ray passes within rounding of a silhouette.
    ranryu::test::context();
    const auto scene = ranryu::scene::parse(small_scene(2), "subparticle_test");
    constexpr int kW = 160, kH = 120;
    std::vector<std::uint8_t> images[2];
    std::uint64_t most = 0;
    for (const char* raster : {"draw", "compute"}) {
        INFO("RANRYU_PARTICLE_RASTER=" << raster);
        ::setenv("RANRYU_PARTICLE_RASTER", raster, 1);
        ranryu::frame::Pipeline pipeline(scene, rig().shaders, kW, kH, ranryu::render::Shading::particles);
        ::unsetenv("RANRYU_PARTICLE_RASTER");
        REQUIRE(pipeline.subparticles() != nullptr);
        REQUIRE(ranryu::frame::run_frames(pipeline, 3) == 3);
        pipeline.drain();
        const bool compute = std::string(raster) == "compute";
        CHECK((find_pass(pipeline.timer(), "draw-particles.rasterise") != nullptr) == compute);
        most = std::max(most, pipeline.subparticles()->stats().most);
        images[compute ? 1 : 0] = ranryu::test::read_rgba(pipeline.target());
    }
    INFO("most sub-particles in a frame: " << most);
    REQUIRE(most > 100);
    int differ = 0, liquid = 0;
    const glm::dvec3 clear = 255.0 * glm::dvec3(0.16, 0.18, 0.22);
    for (std::size_t p = 0; p < std::size_t(kW) * kH; ++p) {
        int err = 0;
        for (int c = 0; c < 3; ++c) err = std::max(err, std::abs(int(images[0][4 * p + c]) - int(images[1][4 * p + c])));
        differ += err > 3;
        liquid += std::abs(double(images[1][4 * p + 2]) - clear.b) > 3.0 && images[1][4 * p + 2] > images[1][4 * p];   // bluish: particles
    }
    INFO(differ << " of " << kW * kH << " pixels differ by more than 3/255; " << liquid << " show particles");
    CHECK(liquid > 200);
    // Silhouette pixels only: the dam break at 4,096 particles differed in 39 of 129,600 (0.03 %).
    CHECK(differ <= kW * kH / 100);
}
