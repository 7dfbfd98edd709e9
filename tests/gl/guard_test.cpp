// The instability guard (engine/sim/guard.*, the records of glsl/sim/fluid/): sim::check() on hand-made
// StepState records, one per criterion; and on the GPU, runs that must be stopped: a fluid far too
// soft for its weight, a compressed state, a NaN written into one velocity, a particle outside the
// tank. Records arrive frames late (an AsyncReadback): each run polls every frame and drains at the
// end, as the app does.
#include "support/gl_fixture.h"
#include "support/sph_rig.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "profile/gpu_timer.h"
#include "reference/sph_reference.h"
#include "scene/scene.h"
#include "shader/source.h"
#include "sim/guard.h"
#include "sim/fluid.h"

namespace {

namespace gpu = ranryu::gpu;
using ranryu::profile::GpuTimer;
using ranryu::sim::GuardLimits;
using ranryu::sim::Instability;

std::uint32_t bits(float f) {
    std::uint32_t b;
    std::memcpy(&b, &f, sizeof b);
    return b;
}

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

struct Rig : ranryu::test::SphRig {
    explicit Rig(const std::string& json) : SphRig(json, "guard_test") {}
};

// 512 particles (8x8x8 at 0.03 m) in a 0.3 m tank, with `solver`; `sph` adds keys to the "sph" object.
// The cases whose numbers follow from WCSPH's equation of state run WCSPH.
std::string scene_json(const std::string& sph = "", const std::string& solver = "wcsph") {
    return R"({"model": "sph", "tank": {"min": [0, 0, 0], "max": [0.3, 0.3, 0.3]}, "sph": {"solver": ")" + solver + "\"" +
           (sph.empty() ? "" : ", " + sph) + R"(},
               "particles": {"spacing": 0.03, "blocks": [{"min": [0, 0, 0], "max": [0.24, 0.24, 0.24]}]}})";
}

// The scene's lattice jittered by ±0.1 dx per axis, at rest, with no pair distance within 1e-5·h of
// h (a lattice distance of exactly h = 2 dx can round to either side of the support in float).
std::vector<glm::vec4> jittered(ranryu::test::Random& rng, const Rig& rig) {
    const float dx = rig.scene.spacing;
    const double h = 2.0 * double(dx);
    for (int attempt = 0; attempt < 100; ++attempt) {
        std::vector<glm::vec4> x = rig.scene.initial_positions();
        for (auto& p : x) p += glm::vec4(rng.uniform(-0.1f, 0.1f), rng.uniform(-0.1f, 0.1f), rng.uniform(-0.1f, 0.1f), 0.0f) * dx;
        bool ok = true;
        for (std::size_t a = 0; a < x.size() && ok; ++a)
            for (std::size_t b = a + 1; b < x.size() && ok; ++b)
                ok = std::abs(glm::length(glm::dvec3(glm::vec3(x[a])) - glm::dvec3(glm::vec3(x[b]))) - h) >= 1e-5 * h;
        if (ok) return x;
    }
    FAIL("no well-posed jitter in 100 draws");
    return {};
}

// One substep of frame `frame` (fixed dt = frame_dt) from the state x, v: its StepState record and the
// state it leaves, read back at once.
struct OneSubstep {
    gpu::StepState record;
    std::vector<glm::vec4> x, v;
};
OneSubstep one_substep(Rig& rig, const std::vector<glm::vec4>& x, const std::vector<glm::vec4>& v, std::uint64_t frame) {
    rig.fluid.upload_state(x, v);
    rig.fluid.set_fixed_dt(rig.scene.frame_dt);
    rig.frame(frame);
    OneSubstep s{rig.fluid.step_state().read<gpu::StepState>(1)[0], rig.read(rig.fluid.positions()), rig.read(rig.fluid.velocities())};
    rig.finish();
    return s;
}

// A sound record: what a quiet frame reports.
gpu::StepState sound_record() {
    gpu::StepState r{};
    r.frame = 7;
    r.steps = 123;
    r.time = 0.5f;
    r.frame_substeps = 10;
    r.frame_min_dt = 1e-4f;
    r.frame_max_density = bits(1.02f);
    r.frame_max_speed = bits(1.5f);
    r.nan_index = r.escaped_index = 0xFFFFFFFFu;
    r.speed_index = 11;
    r.density_index = 12;
    r.speed_position = glm::vec4(0.125f, 0.5f, -0.25f, 0.0f);
    r.density_position = glm::vec4(0.0625f, 0.03125f, 0.75f, 0.0f);
    return r;
}

}  // namespace

TEST_CASE("guard: check() names each criterion and passes a sound record", "[guard]") {
    ranryu::test::context();
    GuardLimits limits;
    limits.density_ratio = 1.5f;
    limits.speed = 10.0f;
    limits.dt_floor = 1e-6f;
    CHECK_FALSE(ranryu::sim::check(sound_record(), limits).has_value());
    {
        // A frame with no substep has no stable dt to judge (frame_min_dt stays +inf).
        gpu::StepState r = sound_record();
        r.frame_substeps = 0;
        r.frame_min_dt = std::numeric_limits<float>::infinity();
        CHECK_FALSE(ranryu::sim::check(r, limits).has_value());
        // At the bounds exactly: still sound.
        r = sound_record();
        r.frame_max_density = bits(1.5f);
        r.frame_max_speed = bits(10.0f);
        r.frame_min_dt = 1e-6f;
        CHECK_FALSE(ranryu::sim::check(r, limits).has_value());
    }
    // Every finding carries the record's frame, substep count and time.
    auto expect = [&](const gpu::StepState& r, const std::string& what) {
        const std::optional<Instability> i = ranryu::sim::check(r, limits);
        INFO("criterion " << what);
        REQUIRE(i.has_value());
        INFO(i->message());
        CHECK(contains(i->criterion, what));
        CHECK(i->frame == 7u);
        CHECK(i->step == 123u);
        CHECK(i->time == Approx(0.5));
        CHECK(contains(i->message(), "frame 7"));
        return *i;
    };
    {
        gpu::StepState r = sound_record();
        r.nan_count = 3;
        r.nan_index = 42;
        r.escaped_count = 1;   // NaN is reported first: it explains everything after it
        r.escaped_index = 5;
        const Instability i = expect(r, "non-finite");
        CHECK(i.particle == 42u);
        CHECK(contains(i.criterion, "3 particle"));
    }
    {
        gpu::StepState r = sound_record();
        r.escaped_count = 2;
        r.escaped_index = 9;
        const Instability i = expect(r, "left the domain");
        CHECK(i.particle == 9u);
        CHECK_FALSE(i.position.has_value());   // the lowest index among them: no one place to name
        CHECK(contains(i.criterion, "2 particles"));
    }
    {
        gpu::StepState r = sound_record();
        r.frame_max_density = bits(1.75f);
        const Instability i = expect(r, "density");
        CHECK(i.particle == 12u);
        CHECK(i.value == Approx(1.75));
        CHECK(i.limit == Approx(1.5));
        CHECK(contains(i.message(), "particle 12 at (0.0625, 0.0312, 0.7500) m: 1.75"));   // where it was

    }
    {
        gpu::StepState r = sound_record();   // a NaN maximum is beyond every bound
        r.frame_max_density = bits(std::numeric_limits<float>::quiet_NaN());
        expect(r, "density");
    }
    {
        gpu::StepState r = sound_record();
        r.frame_max_speed = bits(25.0f);
        const Instability i = expect(r, "speed");
        CHECK(i.particle == 11u);
        CHECK(i.value == Approx(25.0));
        CHECK(i.limit == Approx(10.0));
        CHECK(contains(i.message(), "particle 11 at (0.1250, 0.5000, -0.2500) m: 25"));
    }
    {
        gpu::StepState r = sound_record();
        r.frame_min_dt = 1e-8f;
        const Instability i = expect(r, "time step");
        CHECK(i.value == Approx(1e-8));
        CHECK(i.limit == Approx(1e-6));
    }
    {
        gpu::StepState r = sound_record();
        r.frame_min_dt = 0.0f;   // choose_time_step's dt for NaN maxima
        expect(r, "time step");
    }
    ranryu::test::require_no_gl_errors();
}

TEST_CASE("guard: the dt floor is a hundredth of the stable step at the scene's expected speed, with the Courant number "
          "of the solver in force", "[guard]") {
    // guard_limits(): dt_floor = 0.01 C dx / (c + v) with C the solver's Courant number (sph.dfsph_cfl for
    // DFSPH where set, docs/DFSPH.md (D8); sph.cfl otherwise), c WCSPH's sound speed (0 for DFSPH) and v
    // the scene's speed estimate. The dam break sets cfl 0.4 and dfsph_cfl 0.5: a floor computed from
    // sph.cfl for DFSPH reads 0.8 of it.
    ranryu::scene::Scene s = ranryu::scene::load("dam-break");
    REQUIRE(s.sph.cfl > 0.0f);
    REQUIRE(s.sph.dfsph_cfl > 0.0f);
    REQUIRE(s.sph.dfsph_cfl != s.sph.cfl);
    const double v = double(s.speed_estimate()), dx = double(s.spacing);
    auto floor_of = [&](ranryu::scene::Solver solver) {
        s.sph.solver = solver;
        return double(ranryu::sim::guard_limits(s).dt_floor);
    };
    const double dfsph = floor_of(ranryu::scene::Solver::dfsph), wcsph = floor_of(ranryu::scene::Solver::wcsph);
    const double c = double(s.sound_speed());   // the solver is WCSPH here
    REQUIRE(c > 0.0);
    CHECK(std::abs(dfsph - 0.01 * double(s.sph.dfsph_cfl) * dx / v) <= 1e-6 * dfsph);
    CHECK(std::abs(wcsph - 0.01 * double(s.sph.cfl) * dx / (c + v)) <= 1e-6 * wcsph);
    s.sph.dfsph_cfl = 0.0f;   // unset: DFSPH falls back to sph.cfl
    CHECK(std::abs(floor_of(ranryu::scene::Solver::dfsph) - 0.01 * double(s.sph.cfl) * dx / v) <= 1e-6 * dfsph);
}

TEST_CASE("guard: a density or speed past its bound stops the run when it persists, at once past twice it", "[guard]") {
    // Guard::observe() over a run's records in frame order (sim/guard.h): a frame past a bound and
    // the next within it is a spike; `persist` frames in a row past one stop the run, reported from
    // the first; past hard_factor times a bound (the density by its excess) stops it at once; a
    // non-finite value, an escape or a collapsed step stop it at once whatever the rule.
    GuardLimits limits;
    limits.density_ratio = 1.5f;
    limits.speed = 10.0f;
    limits.dt_floor = 1e-6f;
    limits.persist = 2;
    limits.hard_factor = 2.0f;
    auto frame = [](std::uint64_t f, float density, float speed) {
        gpu::StepState r = sound_record();
        r.frame = std::uint32_t(f);
        r.time = 0.1f * float(f);
        r.frame_max_density = bits(density);
        r.frame_max_speed = bits(speed);
        return r;
    };
    SECTION("a spike passes, and the frames before it and after it are sound") {
        ranryu::sim::Guard g(limits);
        CHECK_FALSE(g.sound_through().has_value());
        CHECK_FALSE(g.observe(frame(0, 1.01f, 2.0f)).has_value());
        CHECK(g.sound_through() == std::optional<std::uint64_t>(0));
        CHECK_FALSE(g.observe(frame(1, 1.01f, 19.0f)).has_value());   // past 10, within 20
        CHECK(g.sound_through() == std::optional<std::uint64_t>(0));  // frame 1 waits for frame 2
        CHECK_FALSE(g.observe(frame(2, 1.01f, 3.0f)).has_value());
        CHECK(g.sound_through() == std::optional<std::uint64_t>(2));
        CHECK(g.spikes() == 1);
        REQUIRE(g.largest_spike().has_value());
        CHECK(g.largest_spike()->frame == 1u);
        CHECK(g.largest_spike()->value == Approx(19.0));
        CHECK(contains(g.largest_spike()->criterion, "speed"));
        CHECK(contains(g.largest_spike()->detail(), "particle 11 at (0.1250, 0.5000, -0.2500) m: 19"));   // the run's spike line
        CHECK_FALSE(g.observe(frame(3, 1.9f, 2.0f)).has_value());     // density 1.9: past 1.5, within 2.0
        CHECK_FALSE(g.observe(frame(4, 1.2f, 2.0f)).has_value());
        CHECK(g.spikes() == 2);
        CHECK(g.largest_spike()->frame == 1u);   // 19/10 against 1.9/1.5
    }
    SECTION("two frames in a row past a bound stop the run, from the first") {
        ranryu::sim::Guard g(limits);
        CHECK_FALSE(g.observe(frame(0, 1.01f, 2.0f)).has_value());
        CHECK_FALSE(g.observe(frame(1, 1.6f, 2.0f)).has_value());
        const std::optional<Instability> i = g.observe(frame(2, 1.01f, 12.0f));   // density, then speed: still a run
        REQUIRE(i.has_value());
        INFO(i->message());
        CHECK(i->frame == 1u);
        CHECK(i->value == Approx(1.6));
        CHECK(contains(i->criterion, "density"));
        CHECK(contains(i->criterion, "2 frames in a row"));
        CHECK(g.spikes() == 0);
    }
    SECTION("past twice a bound stops it at once") {
        ranryu::sim::Guard g(limits);
        std::optional<Instability> i = g.observe(frame(0, 1.01f, 20.5f));
        REQUIRE(i.has_value());
        CHECK(contains(i->criterion, "speed"));
        CHECK(contains(i->criterion, "stopped at once"));
        CHECK(i->limit == Approx(10.0));
        ranryu::sim::Guard d(limits);
        i = d.observe(frame(0, 2.05f, 1.0f));
        REQUIRE(i.has_value());
        CHECK(contains(i->criterion, "density"));
        CHECK(i->limit == Approx(1.5));
    }
    SECTION("a NaN, an escape or a collapsed step stops it at once") {
        gpu::StepState r = frame(0, 1.01f, 2.0f);
        r.nan_count = 1;
        CHECK(ranryu::sim::Guard(limits).observe(r).has_value());
        r = frame(0, 1.01f, 2.0f);
        r.escaped_count = 1;
        CHECK(ranryu::sim::Guard(limits).observe(r).has_value());
        r = frame(0, 1.01f, 2.0f);
        r.frame_min_dt = 1e-8f;
        CHECK(ranryu::sim::Guard(limits).observe(r).has_value());
        r = frame(0, std::numeric_limits<float>::quiet_NaN(), 2.0f);
        CHECK(ranryu::sim::Guard(limits).observe(r).has_value());
    }
    SECTION("persist 1 is the rule of check() alone") {
        limits.persist = 1;
        ranryu::sim::Guard g(limits);
        const std::optional<Instability> i = g.observe(frame(0, 1.01f, 11.0f));
        REQUIRE(i.has_value());
        CHECK(i->frame == 0u);
    }
}

TEST_CASE("guard: a fluid far too soft for its weight is stopped", "[guard]") {
    // c = 0.05 m/s: B = ρ0c²/7 = 0.36 Pa, while holding up a 0.24 m column takes ρ0·g·H = 2.4 kPa at
    // the floor, i.e. ρ/ρ0 = (1 + 2.4e3/0.36)^(1/7) ≈ 3.5, far past the guard's 1.5. The block falls
    // into itself: ρ/ρ0 passes 1.5 once layers close in by 13 % of their spacing (1.5^(-1/3) = 0.87),
    // a fall of ~4 mm (tens of ms); the bound of 60 frames (1 s) also covers the whole column's free
    // fall, sqrt(2H/g) = 0.22 s, and the records' latency (4 frames in flight). Any of the criteria
    // that a blow-up trips first (density, speed, time step) is a right answer.
    ranryu::test::Random rng;
    INFO("seed " << rng.seed());
    Rig rig(scene_json(R"("speed_of_sound": 0.05)"));
    const int bound = 60;
    int frames = 0;
    while (frames < bound && !rig.fluid.instability()) rig.frame(std::uint64_t(frames++));
    rig.finish();
    REQUIRE(rig.fluid.instability().has_value());
    const Instability& i = *rig.fluid.instability();
    INFO(i.message() << " (after " << frames << " frames issued)");
    CHECK((contains(i.criterion, "density") || contains(i.criterion, "speed") || contains(i.criterion, "time step")));
    CHECK(i.frame < std::uint64_t(frames));
    CHECK(i.step > 0u);
    CHECK(i.time > 0.0);
    // Simulated time covers the frames up to this one (each frame_dt, plus what a frame carried over).
    CHECK(i.time <= (double(i.frame) + 2.0) * rig.scene.frame_dt);
    CHECK(i.particle < rig.fluid.count());
    if (contains(i.criterion, "density") || contains(i.criterion, "speed")) CHECK(i.value > i.limit);
    ranryu::test::require_no_gl_errors();
}

TEST_CASE("guard: a state compressed past the density bound is reported in its first frame", "[guard]") {
    // The block on a lattice of pitch 0.82 dx: ρ/ρ0 ≈ 1/0.82³ = 1.8 inside, past the bound 1.5 before
    // any step is taken. The record's density is the largest ρ/ρ0 that the density pass saw. (Harder
    // still, pitch 0.7, ρ/ρ0 ≈ 2.9, p ≈ 2000 B: the one substep, whose dt comes from the previous
    // maxima, throws particles out of the tank, and the guard reports the escape, which it checks first.)
    ranryu::test::Random rng;
    INFO("seed " << rng.seed());
    Rig rig(scene_json());
    const float dx = rig.scene.spacing;
    std::vector<glm::vec4> x = rig.scene.initial_positions(), v(x.size(), glm::vec4(0.0f));
    for (auto& p : x) p = glm::vec4(glm::vec3(0.05f) + (glm::vec3(p) - glm::vec3(0.5f * dx)) * 0.82f +
                                        glm::vec3(rng.uniform(-0.05f, 0.05f), rng.uniform(-0.05f, 0.05f), rng.uniform(-0.05f, 0.05f)) * dx,
                                    0.0f);
    rig.fluid.upload_state(x, v);
    rig.fluid.set_fixed_dt(rig.scene.frame_dt);   // one substep
    rig.frame(0);
    const auto density = rig.read(rig.fluid.densities());
    rig.finish();
    REQUIRE(rig.fluid.instability().has_value());
    const Instability& i = *rig.fluid.instability();
    INFO(i.message());
    CHECK(contains(i.criterion, "density"));
    CHECK(i.frame == 0u);
    CHECK(i.step == 1u);
    float most = 0.0f;
    for (const glm::vec4& d : density) most = std::max(most, d.x / rig.fluid.params().rest_density);
    CHECK(most > 1.6f);
    CHECK(float(i.value) == Approx(most).epsilon(1e-6));
    CHECK(i.particle < rig.fluid.count());
    // Where the densest particle was when the density pass read it: one of the uploaded positions
    // (the sort moves them bitwise), and inside the compressed block (its edges are less dense).
    REQUIRE(i.position.has_value());
    const glm::vec3 at = *i.position;
    CHECK(std::any_of(x.begin(), x.end(), [&](const glm::vec4& p) { return glm::vec3(p) == at; }));
    glm::vec3 lo(1e9f), hi(-1e9f);
    for (const glm::vec4& p : x) lo = glm::min(lo, glm::vec3(p)), hi = glm::max(hi, glm::vec3(p));
    INFO("densest at (" << at.x << ", " << at.y << ", " << at.z << "), the block within (" << lo.x << ".." << hi.x << ")");
    CHECK(glm::all(glm::greaterThan(at, lo)));
    CHECK(glm::all(glm::lessThan(at, hi)));
    ranryu::test::require_no_gl_errors();
}

TEST_CASE("guard: the frame's fastest particle is named with where its step ended", "[guard]") {
    // One substep (fixed dt = frame_dt) of the jittered block at rest, one random particle given 2-3 m/s
    // in a random direction within 45 degrees of +x (it stays inside the tank: 0.05 m in the step, and the
    // block leaves 0.06 m free on that side; towards −x a particle on the wall's face was stopped by the
    // wall below 1 m/s, seed 2509811392 with DFSPH).
    // The record names the fastest particle after the step; the position it carries is that particle's
    // position as the step left it, exactly (the integration writes both), for either solver.
    ranryu::test::Random rng;
    INFO("seed " << rng.seed());
    const std::string solver = GENERATE(as<std::string>(), "wcsph", "dfsph");
    INFO(solver);
    Rig rig(scene_json("", solver));
    std::vector<glm::vec4> x = jittered(rng, rig), v(x.size(), glm::vec4(0.0f));
    const std::size_t shot = rng.below(unsigned(x.size()));
    rng.uniform(0.0f, 1.0f);   // the draw that chose −x or +x, kept so that a seed gives the same particles
    const glm::vec3 dir = glm::normalize(glm::vec3(1.0f, rng.uniform(-0.7f, 0.7f), rng.uniform(-0.7f, 0.7f)));
    v[shot] = glm::vec4(rng.uniform(2.0f, 3.0f) * dir, 0.0f);
    INFO("input particle " << shot << " at " << glm::length(glm::vec3(v[shot])) << " m/s");
    const auto [record, xs, vs] = one_substep(rig, x, v, 0);
    std::uint32_t fastest = 0;
    for (std::uint32_t k = 1; k < vs.size(); ++k)
        if (glm::length(glm::vec3(vs[k])) > glm::length(glm::vec3(vs[fastest]))) fastest = k;
    float speed;
    std::memcpy(&speed, &record.frame_max_speed, sizeof speed);
    CHECK(record.frame_substeps == 1u);
    CHECK(speed == Approx(glm::length(glm::vec3(vs[fastest]))).epsilon(1e-6));
    CHECK(speed > 1.0f);   // the shot particle, not one it pushed
    CHECK(record.speed_index == fastest);
    CHECK(glm::vec3(record.speed_position) == glm::vec3(xs[fastest]));
    ranryu::test::require_no_gl_errors();
}

TEST_CASE("guard: the frame's fastest and densest particles are named exactly across workgroups and frames", "[guard]") {
    // 13,824 particles (a 24³ jittered lattice at dx = 0.0125 m): 108 workgroups of the density pass
    // (54 of WCSPH's and DFSPH's integrations), 108 spans of FrameExtreme entries (shared/bindings.h).
    // The speeds grow with height (with a random part), and the particles are sorted by cell, so most workgroups in turn
    // raise the maximum: where the index was written after an atomicMax, two workgroups wrote in
    // either order and the record could name a slower particle (it did on the NVIDIA driver). One
    // substep a frame (frame_dt 0.2 ms: a particle moves less than 0.02 dx); the second frame is
    // slower and sparser (the block spread by 3 %), so its record is its own only if the first frame's
    // entries were cleared. Reference: the state read back, the record exact (the fastest particle's
    // speed, index and end position; the densest particle's density within float ties) and where the
    // density pass read the densest particle: within 0.25 dx of its end position and, for WCSPH and
    // DFSPH, one of the uploaded positions bit for bit (the sort moves them bitwise; PBF's density is
    // that of its last iteration's predicted positions).
    ranryu::test::Random rng;
    INFO("seed " << rng.seed());
    const std::string solver = GENERATE(as<std::string>(), "wcsph", "dfsph", "pbf");
    INFO(solver);
    Rig rig(R"({"model": "sph", "tank": {"min": [0, 0, 0], "max": [0.5, 0.5, 0.5]}, "time": {"frame_dt": 0.0002},
               "sph": {"solver": ")" + solver + R"("},
               "particles": {"spacing": 0.0125, "blocks": [{"min": [0.1, 0.02, 0.1], "max": [0.4, 0.32, 0.4]}]}})");
    REQUIRE(rig.fluid.count() == 13824u);
    const float dx = rig.scene.spacing;
    std::vector<glm::vec4> x = rig.scene.initial_positions();
    for (auto& p : x) p += glm::vec4(rng.uniform(-0.1f, 0.1f), rng.uniform(-0.1f, 0.1f), rng.uniform(-0.1f, 0.1f), 0.0f) * dx;
    const float rho0 = rig.fluid.params().rest_density;
    float first_speed = 0.0f, first_ratio = 0.0f;
    for (int frame = 0; frame < 2; ++frame) {
        INFO("frame " << frame);
        if (frame == 1)
            for (auto& p : x) p = glm::vec4(glm::vec3(0.25f, 0.02f, 0.25f) + 1.03f * (glm::vec3(p) - glm::vec3(0.25f, 0.02f, 0.25f)), 0.0f);
        const float top = frame == 0 ? 0.5f : 0.2f, bottom = frame == 0 ? 0.25f : 0.0f;   // m/s
        std::vector<glm::vec4> v(x.size());
        for (std::size_t k = 0; k < x.size(); ++k) {
            const float up = (x[k].y - 0.02f) / 0.3f;
            const glm::vec3 dir = glm::normalize(glm::vec3(rng.uniform(-1.0f, 1.0f), rng.uniform(-1.0f, 1.0f), rng.uniform(-1.0f, 1.0f)) + 1e-3f);
            v[k] = glm::vec4(dir * (bottom + (top - bottom) * (0.9f * up + 0.1f * rng.uniform(0.0f, 1.0f))), 0.0f);
        }
        rig.fluid.upload_state(x, v);
        rig.fluid.set_fixed_dt(rig.scene.frame_dt);
        rig.frame(std::uint64_t(frame));
        const gpu::StepState record = rig.step();
        const auto xs = rig.read(rig.fluid.positions()), vs = rig.read(rig.fluid.velocities()), density = rig.read(rig.fluid.densities());
        rig.finish();
        REQUIRE(record.frame_substeps == 1u);
        std::uint32_t fastest = 0, densest = 0;
        for (std::uint32_t k = 1; k < vs.size(); ++k) {
            if (glm::length(glm::vec3(vs[k])) > glm::length(glm::vec3(vs[fastest]))) fastest = k;
            if (density[k].x > density[densest].x) densest = k;
        }
        float speed, ratio;
        std::memcpy(&speed, &record.frame_max_speed, sizeof speed);
        std::memcpy(&ratio, &record.frame_max_density, sizeof ratio);
        INFO("fastest " << fastest << " at " << glm::length(glm::vec3(vs[fastest])) << " m/s, record " << record.speed_index << " at " << speed);
        if (frame == 1) {   // the case's premise: the first frame's maxima exceed the second's
            REQUIRE(glm::length(glm::vec3(vs[fastest])) < first_speed);
            REQUIRE(density[densest].x / rho0 < first_ratio);
        }
        CHECK(speed == Approx(glm::length(glm::vec3(vs[fastest]))).epsilon(1e-6));
        CHECK(record.speed_index == fastest);
        CHECK(glm::vec3(record.speed_position) == glm::vec3(xs[fastest]));
        INFO("densest " << densest << " at " << density[densest].x / rho0 << ", record " << record.density_index << " at " << ratio);
        CHECK(ratio == Approx(density[densest].x / rho0).epsilon(1e-6));
        REQUIRE(record.density_index < density.size());
        CHECK(density[record.density_index].x == Approx(density[densest].x).epsilon(1e-6));
        const glm::vec3 at(record.density_position);
        CHECK(glm::length(at - glm::vec3(xs[record.density_index])) < 0.25f * dx);
        if (solver != "pbf") CHECK(std::any_of(x.begin(), x.end(), [&](const glm::vec4& p) { return glm::vec3(p) == at; }));
        first_speed = speed;
        first_ratio = ratio;
    }
    ranryu::test::require_no_gl_errors();
}

TEST_CASE("guard: the frame's fastest particle is kept from the step it was fastest in, not the frame's last", "[guard]") {
    // Two substeps a frame. One particle shot upwards at 2.5-3 m/s, farther than h from every other
    // particle and from the walls, slows a step (a = g exactly: no neighbour), so the frame's fastest
    // is that particle at the end of the first substep; the second substep's smaller value must not
    // replace it in its workgroup's entry. The second substep (its dt the record's) took it from x1,
    // v1 to x2 = x1 + dt v2, v2 = v1 + dt g (symplectic Euler, docs/SPH.md (6)), so the record must hold
    // |v2 − dt g| and x2 − dt v2. The block below moves far slower.
    ranryu::test::Random rng;
    INFO("seed " << rng.seed());
    std::string json = scene_json();
    json.insert(1, R"("time": {"frame_dt": 0.002}, )");   // a frame of 2 ms, in two substeps (below)
    Rig rig(json);
    std::vector<glm::vec4> x = jittered(rng, rig), v(x.size(), glm::vec4(0.0f));
    const std::size_t shot = rng.below(unsigned(x.size()));
    const glm::vec3 x0(rng.uniform(0.12f, 0.18f), 0.29f, rng.uniform(0.12f, 0.18f));
    const glm::vec3 v0(rng.uniform(-0.1f, 0.1f), rng.uniform(2.5f, 3.0f), rng.uniform(-0.1f, 0.1f));
    x[shot] = glm::vec4(x0, 0.0f);
    v[shot] = glm::vec4(v0, 0.0f);
    const float h = 2.0f * rig.scene.spacing;
    for (std::size_t k = 0; k < x.size(); ++k)
        if (k != shot) REQUIRE(glm::length(glm::vec3(x[k]) - x0) > h);   // the block's top is below 0.23 m
    rig.fluid.upload_state(x, v);
    rig.fluid.set_fixed_dt(0.001f);   // two substeps; each as long as the CFL condition allows
    rig.frame(0);
    const gpu::StepState record = rig.step();
    const auto xs = rig.read(rig.fluid.positions()), vs = rig.read(rig.fluid.velocities());
    rig.finish();
    REQUIRE(record.frame_substeps == 2u);
    std::size_t fastest = 0;   // after the second substep: the shot particle (sorted index)
    for (std::size_t k = 1; k < vs.size(); ++k)
        if (glm::length(glm::vec3(vs[k])) > glm::length(glm::vec3(vs[fastest]))) fastest = k;
    const float dt = record.dt;
    const glm::vec3 g = rig.scene.gravity, x2(xs[fastest]), v2(vs[fastest]), v1 = v2 - dt * g, x1 = x2 - dt * v2;
    float speed;
    std::memcpy(&speed, &record.frame_max_speed, sizeof speed);
    INFO("dt " << dt << " s; recorded " << speed << " m/s, the first substep's " << glm::length(v1) << ", the second's "
               << glm::length(v2));
    REQUIRE(glm::length(glm::vec3(x0) - x2) < 0.01f);                  // the premise: that is the shot particle,
    REQUIRE(glm::length(v2) < glm::length(v1) - 0.5f * 9.81f * dt);   // and it slowed
    CHECK(speed == Approx(glm::length(v1)).epsilon(1e-5));
    CHECK(glm::length(glm::vec3(record.speed_position) - x1) < 1e-6f);
    ranryu::test::require_no_gl_errors();
}

TEST_CASE("guard: the frame's extremes fold to the largest entry, ties to the lowest, and are cleared", "[guard]") {
    // record_extremes.comp against a CPU fold of fresh random FrameExtreme entries: 64,000 particles,
    // 500 spans (two rounds of the pass's 256 invocations), values from a set of eight so that ties
    // are common, a fifth of the entries empty; where a kind has no entry at all (second round), its
    // record is zero. The entries are read back zero afterwards, the particles' state untouched.
    ranryu::test::Random rng;
    INFO("seed " << rng.seed());
    Rig rig(R"({"model": "sph", "tank": {"min": [0, 0, 0], "max": [0.5, 0.5, 0.5]}, "sph": {"solver": "wcsph"},
               "particles": {"spacing": 0.01, "blocks": [{"min": [0, 0, 0], "max": [0.4, 0.4, 0.4]}]}})");
    REQUIRE(rig.fluid.count() == 64000u);
    const std::size_t spans = (rig.fluid.count() + RANRYU_EXTREME_SPAN - 1) / RANRYU_EXTREME_SPAN;
    REQUIRE(spans == 500u);
    REQUIRE(rig.fluid.step_state().size() == sizeof(gpu::StepState) + 2 * spans * sizeof(gpu::FrameExtreme));
    for (int round = 0; round < 2; ++round) {
        INFO("round " << round);
        std::vector<gpu::FrameExtreme> e(2 * spans);
        std::uint32_t values[8];
        for (std::uint32_t& b : values) b = bits(rng.uniform(0.5f, 2.0f));
        for (std::size_t k = 0; k < e.size(); ++k) {
            const bool empty = rng.uniform(0.0f, 1.0f) < 0.2f || (round == 1 && k % 2 == RANRYU_EXTREME_DENSITY);
            e[k].bits = empty ? 0u : values[rng.below(8)];
            e[k].index = std::uint32_t(rng.below(64000));
            e[k].position = glm::vec4(rng.uniform(0.0f, 0.5f), rng.uniform(0.0f, 0.5f), rng.uniform(0.0f, 0.5f), 0.0f);
        }
        const auto before = rig.read(rig.fluid.positions());
        glBindBuffer(GL_COPY_WRITE_BUFFER, rig.fluid.step_state().id());
        glBufferSubData(GL_COPY_WRITE_BUFFER, GLintptr(sizeof(gpu::StepState)), GLsizeiptr(e.size() * sizeof e[0]), e.data());
        glBindBuffer(GL_COPY_WRITE_BUFFER, 0);
        rig.timer.begin_frame();
        rig.fluid.begin_frame(std::uint64_t(round));
        rig.fluid.end_frame();
        rig.timer.end_frame();
        rig.fluid.poll_records();
        const gpu::StepState r = rig.step();
        const auto after = rig.fluid.step_state().read<gpu::FrameExtreme>(2 * spans, sizeof(gpu::StepState));
        CHECK(rig.read(rig.fluid.positions()) == before);
        rig.finish();
        for (std::uint32_t kind : {std::uint32_t(RANRYU_EXTREME_SPEED), std::uint32_t(RANRYU_EXTREME_DENSITY)}) {
            INFO("kind " << kind);
            std::size_t best = e.size();
            for (std::size_t k = kind; k < e.size(); k += 2)
                if (e[k].bits != 0u && (best == e.size() || e[k].bits > e[best].bits)) best = k;
            const bool any = best != e.size();
            const std::uint32_t want_bits = any ? e[best].bits : 0u, want_index = any ? e[best].index : 0u;
            const glm::vec4 want_at = any ? e[best].position : glm::vec4(0.0f);
            const bool speed = kind == RANRYU_EXTREME_SPEED;
            CHECK((speed ? r.frame_max_speed : r.frame_max_density) == want_bits);
            CHECK((speed ? r.speed_index : r.density_index) == want_index);
            CHECK((speed ? r.speed_position : r.density_position) == want_at);
        }
        std::size_t left = 0;
        for (const gpu::FrameExtreme& f : after) left += f.bits != 0u;
        CHECK(left == 0u);
    }
    ranryu::test::require_no_gl_errors();
}

TEST_CASE("guard: a NaN written into one velocity is reported as non-finite", "[guard]") {
    // One substep (fixed dt = frame_dt): the poisoned particle's update is NaN, and so is each
    // neighbour's, through the viscous term (v_ij · x_ij with v_i NaN) over pairs closer than h. So
    // the record counts exactly the poisoned particle's neighbour set (itself included, reference
    // brute force) and names the lowest sorted index among them: where the read-back state is NaN.
    ranryu::test::Random rng;
    INFO("seed " << rng.seed());
    Rig rig(scene_json());
    std::vector<glm::vec4> x = jittered(rng, rig), v(x.size(), glm::vec4(0.0f));
    const std::size_t poisoned = rng.below(unsigned(x.size()));
    INFO("NaN in the velocity of input particle " << poisoned);
    v[poisoned].y = std::numeric_limits<float>::quiet_NaN();
    std::vector<glm::dvec3> xd(x.size());
    for (std::size_t k = 0; k < x.size(); ++k) xd[k] = glm::dvec3(glm::vec3(x[k]));
    const std::size_t spread = ranryu::reference::neighbours(xd, 2.0 * double(rig.scene.spacing))[poisoned].size();

    const auto [record, xs, vs] = one_substep(rig, x, v, 3);
    std::vector<std::uint32_t> bad;
    for (std::uint32_t k = 0; k < xs.size(); ++k)
        if (glm::any(glm::isnan(glm::vec3(xs[k]))) || glm::any(glm::isnan(glm::vec3(vs[k])))) bad.push_back(k);
    INFO(bad.size() << " non-finite particles after the substep; the poisoned one has " << spread << " neighbours");
    CHECK(record.frame_substeps == 1u);
    CHECK(record.nan_count == spread);
    CHECK(bad.size() == spread);
    REQUIRE_FALSE(bad.empty());
    CHECK(record.nan_index == bad.front());
    REQUIRE(rig.fluid.instability().has_value());
    const Instability& i = *rig.fluid.instability();
    INFO(i.message());
    CHECK(contains(i.criterion, "non-finite"));
    CHECK(i.particle == record.nan_index);
    CHECK(i.particle < rig.fluid.count());
    CHECK(i.frame == 3u);
    CHECK(i.step == 1u);
    ranryu::test::require_no_gl_errors();
}

TEST_CASE("guard: a particle outside the tank is reported as having left the domain", "[guard]") {
    // The guard's domain is the tank grown by dx at the walls and floor (fluid.cpp, sph_params). One
    // particle goes 4 dx beyond a wall (past the 3 boundary layers, still inside the neighbour grid),
    // or 4 dx below the floor; one substep: the record counts one escapee and names its sorted index.
    ranryu::test::Random rng;
    INFO("seed " << rng.seed());
    const bool below = GENERATE(false, true);
    const std::string solver = GENERATE(as<std::string>(), "wcsph", "dfsph");
    INFO((below ? "below the floor" : "beyond the +x wall") << ", " << solver);
    Rig rig(scene_json("", solver));
    const float dx = rig.scene.spacing;
    std::vector<glm::vec4> x = jittered(rng, rig), v(x.size(), glm::vec4(0.0f));
    const std::size_t moved = rng.below(unsigned(x.size()));
    x[moved] = below ? glm::vec4(0.15f, rig.scene.tank_min.y - 4.0f * dx, 0.15f, 0.0f)
                     : glm::vec4(rig.scene.tank_max.x + 4.0f * dx, 0.15f, 0.15f, 0.0f);
    // Either place is more than h from every other particle of the block ([0, 0.24]^3): it feels no
    // fluid, only boundary particles, and no pressure (p = 0 at its low density).
    const auto [record, xs, vs] = one_substep(rig, x, v, 0);
    const glm::vec3 lo(rig.fluid.params().domain_min), hi(rig.fluid.params().domain_max);
    std::vector<std::uint32_t> outside;
    for (std::uint32_t k = 0; k < xs.size(); ++k)
        if (glm::any(glm::lessThan(glm::vec3(xs[k]), lo)) || glm::any(glm::greaterThan(glm::vec3(xs[k]), hi))) outside.push_back(k);
    REQUIRE(outside.size() == 1);
    CHECK(record.escaped_count == 1u);
    CHECK(record.escaped_index == outside.front());
    CHECK(record.nan_count == 0u);
    REQUIRE(rig.fluid.instability().has_value());
    const Instability& i = *rig.fluid.instability();
    INFO(i.message());
    CHECK(contains(i.criterion, "1 particles left the domain"));
    CHECK(i.particle == outside.front());
    CHECK(i.frame == 0u);
    ranryu::test::require_no_gl_errors();
}
