// The emitter (sim/fluid.h, glsl/sim/fluid/emit_particles.comp): a budget of particles allocated at
// start, the scene's and the rest parked; "emit" pours one sheet of the nozzle's lattice from the
// parked ones a call, on the GPU, until none is left. Checked against the CPU's sheet
// (emitter_for()) on a scene of random size and budget: the poured positions are the sheet's slots,
// each once, with its velocity; the rest stay parked where they were; StepState.live_count counts them;
// and a frame with parked particles runs without a guard finding or a parked particle moving.
#include "support/gl_fixture.h"
#include "support/sph_rig.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <tuple>
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"
#include "sim/fluid.h"

namespace {

using ranryu::scene::Scene;

// The sheet's slots, as the pass places them (emit_particles.comp's formula, in double).
std::vector<glm::dvec3> sheet(const ranryu::sim::EmitterShape& e, double dx) {
    std::vector<glm::dvec3> out;
    for (int k = 0; k < e.side * e.side; ++k)
        out.push_back(glm::dvec3(e.nozzle) + dx * glm::dvec3(double(k % e.side) - 0.5 * (e.side - 1), 0.0,
                                                            double(k / e.side) - 0.5 * (e.side - 1)));
    return out;
}

}  // namespace

TEST_CASE("emitter: each emit pours one sheet of the parked particles onto the nozzle's lattice, up to the budget", "[emitter]") {
    ranryu::test::Random rng;
    INFO("seed " << rng.seed());
    const std::string solver = GENERATE(as<std::string>(), "wcsph", "dfsph");
    INFO(solver);
    // A closed tank of random width (the sheet's side follows it) with a thin pool; a budget of 1.3 to
    // 2.7 sheets beyond the pool, so that the third emit finds fewer parked particles than a sheet.
    const float width = rng.uniform(0.4f, 0.8f);
    Scene s = ranryu::scene::parse(R"({"name": "emitter", "model": "sph", "tank": {"min": [0, 0, 0], "max": [)" + std::to_string(width) +
                                       R"(, 0.5, 0.4], "closed": true},
        "particles": {"spacing": 0.04, "blocks": [{"min": [0, 0, 0], "max": [0.4, 0.08, 0.4]}]},
        "sph": {"solver": ")" + solver + R"("}})",
                                   "emitter_test");
    const ranryu::sim::EmitterShape e = ranryu::sim::emitter_for(s);
    const std::size_t per_sheet = std::size_t(e.side * e.side), n0 = s.particle_count();
    const std::size_t extra = std::size_t(std::lround(double(per_sheet) * rng.uniform(1.3f, 2.7f)));
    s.particle_budget = n0 + extra;
    ranryu::test::SphRig rig(s);
    REQUIRE(rig.fluid.count() == n0 + extra);
    REQUIRE(rig.fluid.has_budget());
    const double dx = s.spacing;
    const std::vector<glm::dvec3> slots = sheet(e, dx);
    INFO("side " << e.side << ", " << extra << " parked beyond the scene's " << n0);

    std::vector<glm::vec4> before = rig.read(rig.fluid.positions());
    CHECK(rig.step().live_count == n0);
    std::size_t poured_total = 0;
    for (int call = 0; call < 4; ++call) {
        rig.timer.begin_frame();
        rig.fluid.emit();
        rig.timer.end_frame();
        const std::vector<glm::vec4> x = rig.read(rig.fluid.positions()), v = rig.read(rig.fluid.velocities());
        const std::size_t want = std::min(per_sheet, extra - poured_total);
        std::vector<int> taken(slots.size(), 0);
        std::size_t poured = 0, moved_parked = 0, stray = 0;
        for (std::size_t i = 0; i < x.size(); ++i) {
            const bool was = before[i].w < -0.5f, is = x[i].w < -0.5f;
            if (was && !is) {
                ++poured;
                // Its slot: the nearest; float rounding of a few ulp of 1 m, bound 1e-6 m.
                std::size_t best = 0;
                for (std::size_t k = 1; k < slots.size(); ++k)
                    if (glm::length(slots[k] - glm::dvec3(glm::vec3(x[i]))) < glm::length(slots[best] - glm::dvec3(glm::vec3(x[i])))) best = k;
                stray += glm::length(slots[best] - glm::dvec3(glm::vec3(x[i]))) > 1e-6;
                ++taken[best];
                CHECK(glm::vec3(v[i]) == e.velocity);
            } else if (x[i] != before[i]) {
                ++moved_parked;   // a parked one that stayed, or an active one: untouched
            }
        }
        INFO("emit " << call << ": poured " << poured << " (want " << want << ")");
        CHECK(poured == want);
        CHECK(stray == 0u);
        CHECK(moved_parked == 0u);
        CHECK(*std::max_element(taken.begin(), taken.end()) <= 1);   // a slot once
        poured_total += poured;
        CHECK(rig.step().live_count == n0 + poured_total);
        before = x;
    }
    CHECK(poured_total == extra);   // the budget spent, and not beyond: the fourth emit found none

    // Whole frames with parked particles (a fresh rig: the sheets above overlap, never poured so):
    // the guard finds nothing, the parked stay put, and active stays the scene's without emitting.
    ranryu::test::SphRig fresh(s);
    const std::vector<glm::vec4> x0 = fresh.read(fresh.fluid.positions());
    std::vector<glm::vec4> parked0;
    for (const glm::vec4& p : x0)
        if (p.w < -0.5f) parked0.push_back(p);
    for (int f = 0; f < 3; ++f) fresh.frame(std::uint64_t(f));
    const std::vector<glm::vec4> x1 = fresh.read(fresh.fluid.positions());
    std::vector<glm::vec4> parked1;
    for (const glm::vec4& p : x1)
        if (p.w < -0.5f) parked1.push_back(p);
    const auto order = [](const glm::vec4& a, const glm::vec4& b) { return std::tie(a.x, a.y, a.z) < std::tie(b.x, b.y, b.z); };
    std::sort(parked0.begin(), parked0.end(), order);
    std::sort(parked1.begin(), parked1.end(), order);
    CHECK(parked1 == parked0);
    CHECK(fresh.step().live_count == n0);
    fresh.finish();
    INFO((fresh.fluid.instability() ? fresh.fluid.instability()->message() : std::string("stable")));
    CHECK_FALSE(fresh.fluid.instability().has_value());
    ranryu::test::require_no_gl_errors();
}
