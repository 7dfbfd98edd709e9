// sim/fluid.h planning_record(): the CPU plans each frame (its substeps; DFSPH's iteration caps) from
// the record of the frame simulated Fluid::plan_lag() frames before, never from a newer one that
// happened to come back already. So a run does not depend on how fast its records come back: one that
// waits for every record at the end of each frame (the newest record always the frame just run) and
// one whose records are handed over only when the readback ring needs their slot again (the latest
// the ring allows, as the slowest GPU would return them) are the same run, to the bit.
#include "support/gl_fixture.h"

#include <cstring>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "frame/loop.h"
#include "frame/pipeline.h"
#include "scene/scene.h"
#include "shader/source.h"
#include "sim/fluid.h"

using namespace ranryu;

namespace {

struct Planned {
    std::uint64_t frame;                        // the pipeline's frame number
    int substeps;                               // issued this frame
    std::optional<std::uint64_t> from;          // the frame whose record planned it
    std::optional<std::uint64_t> newest;        // the newest record at hand after the frame
};

enum class Records { waited_for, late };   // every frame's own at its end; only as the ring reuses slots

struct Run {
    std::vector<Planned> planned;
    std::vector<glm::vec4> x, v;
};

// `frames` frames of `s`, frame `held` held (run's pause: drawn, not simulated).
Run run(const scene::Scene& s, std::uint64_t frames, std::uint64_t held, Records records) {
    frame::View view;
    view.draw = false;
    frame::Pipeline p(s, shader::FileSource::embedded(), view);
    if (records == Records::late) p.simulation()->fluid().hand_over_records_late(true);
    Run r;
    std::uint64_t simulated = 0;
    frame::FrameHooks hooks;
    hooks.advance = [held](const frame::Pipeline& q) { return q.frames() != held; };
    hooks.after = [&](frame::Pipeline& q) {
        if (q.simulated_frames() == simulated) return;   // held
        simulated = q.simulated_frames();
        const sim::Fluid& f = q.simulation()->fluid();
        Planned e{q.frames() - 1, f.substeps_this_frame(), std::nullopt, std::nullopt};
        if (f.planning_record()) e.from = f.planning_record()->frame;
        if (records == Records::waited_for) {
            q.drain();
            q.poll();
        }
        if (f.last_record()) e.newest = f.last_record()->frame;
        r.planned.push_back(e);
    };
    frame::run_frames(p, frames, hooks);
    p.drain();
    p.poll();
    r.x = p.positions().read<glm::vec4>(p.particle_count());
    r.v = p.velocities().read<glm::vec4>(p.particle_count());
    return r;
}

bool same_bits(const std::vector<glm::vec4>& a, const std::vector<glm::vec4>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(glm::vec4)) == 0;
}

}  // namespace

TEST_CASE("plan: each frame is planned from the record plan_lag simulated frames back, so a run does not depend on its "
          "readbacks' timing",
          "[plan]") {
    test::context();
    test::Random rng;
    INFO("seed " << rng.seed());
    // The two solvers whose plan reads the records (PBF's substeps are fixed), over the dam break at a
    // coarse spacing (llvmpipe): 12 frames, one of them held, so that 11 - plan_lag are planned from
    // records, and the one held falls before or among them.
    for (const scene::Solver solver : {scene::Solver::dfsph, scene::Solver::wcsph}) {
        scene::Scene s = scene::load("dam-break");
        s = scene::with_spacing(s, s.spacing * rng.uniform(1.8f, 2.4f), "test");
        s.sph.solver = solver;
        // DFSPH's step at this spacing is its upper bound in the first 12 frames (the CFL step
        // lambda dx / v_max is longer there: 18 ms at 0.03 m and 0.8 m/s), so every frame would plan
        // the same substeps whatever the records said; with the frame as the bound the CFL step sets
        // the plan, and the records change it as the column gathers speed.
        if (solver == scene::Solver::dfsph) s.sph.max_time_step = s.frame_dt;
        const std::uint64_t frames = 12, held = 2 + rng.below(4);
        INFO(scene::solver_name(solver) << " at " << s.spacing << " m, frame " << held << " held");
        const Run waiting = run(s, frames, held, Records::waited_for), late = run(s, frames, held, Records::late);
        REQUIRE(waiting.planned.size() == frames - 1);
        REQUIRE(late.planned.size() == frames - 1);
        const std::size_t lag = std::size_t(sim::Fluid::record_depth(s)) + 1;
        REQUIRE(lag >= 2);
        for (std::size_t k = 0; k < waiting.planned.size(); ++k) {
            const Planned& w = waiting.planned[k];
            const Planned& l = late.planned[k];
            INFO("simulated frame " << k << " (frame " << w.frame << ")");
            if (k < lag) {
                CHECK_FALSE(w.from);
                CHECK_FALSE(l.from);
            } else {
                // The record of the frame simulated plan_lag() before (the held frame made none).
                REQUIRE(w.from);
                REQUIRE(l.from);
                CHECK(*w.from == waiting.planned[k - lag].frame);
                CHECK(*l.from == late.planned[k - lag].frame);
            }
            // The waiting run had this frame's own record at hand when it planned the next, the late
            // run only the one the ring's reuse handed over, record_depth() frames older: neither plan
            // took the newest.
            REQUIRE(w.newest);
            CHECK(*w.newest == w.frame);
            if (k + 1 < lag) {
                CHECK_FALSE(l.newest);
            } else {
                REQUIRE(l.newest);
                CHECK(*l.newest == late.planned[k + 1 - lag].frame);
            }
            CHECK(w.substeps == l.substeps);
        }
        // From the first record on, the plan follows the flow: the dam break's first frames need more
        // substeps than the scene's estimate planned (the test sees the records act).
        bool changed = false;
        for (std::size_t k = lag; k < waiting.planned.size(); ++k) changed |= waiting.planned[k].substeps != waiting.planned[0].substeps;
        CHECK(changed);
        CHECK(same_bits(waiting.x, late.x));
        CHECK(same_bits(waiting.v, late.v));
    }
    test::require_no_gl_errors();
}

TEST_CASE("plan: a frame opened twice, or ended unopened, is refused", "[plan]") {
    test::context();
    scene::Scene s = scene::load("dam-break");
    s = scene::with_spacing(s, s.spacing * 2.0f, "test");
    s.sph.solver = scene::Solver::dfsph;
    frame::View view;
    view.draw = false;
    frame::Pipeline p(s, shader::FileSource::embedded(), view);
    sim::Fluid& f = p.simulation()->fluid();
    // Each frame's record is tagged with the frame it ends, and the plan counts on one a frame.
    p.begin_frame();   // the timers' frame, which the fluid's passes are timed in
    CHECK_THROWS_WITH(f.end_frame(), Catch::Contains("no frame is open"));
    f.begin_frame(0);
    CHECK_THROWS_WITH(f.begin_frame(0), Catch::Contains("the frame before was not ended"));
    CHECK_NOTHROW(f.end_frame());
    CHECK_THROWS_WITH(f.end_frame(), Catch::Contains("no frame is open"));
    p.end_frame();
    p.drain();
    test::require_no_gl_errors();
}
