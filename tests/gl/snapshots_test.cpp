// validation::ParticleSnapshots, the validation cases' per-frame copies of the particle arrays read
// back asynchronously, against the same arrays read back synchronously after each frame (what the
// cases did before): equal to the bit, under each frame's tag, oldest first, every frame delivered.
// And sim::Fluid::stop_particles(), the relaxation's zeroing of the velocities on the GPU.
#include "support/gl_fixture.h"

#include <cstring>
#include <map>
#include <vector>

#include <glm/glm.hpp>

#include "frame/loop.h"
#include "frame/pipeline.h"
#include "scene/scene.h"
#include "shader/source.h"
#include "sim/simulation.h"
#include "validation/cases.h"
#include "validation/snapshots.h"

using namespace ranryu;
using validation::ParticleSnapshots;

namespace {

bool same_bits(std::span<const glm::vec4> a, const std::vector<glm::vec4>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), b.size() * sizeof(glm::vec4)) == 0;
}

frame::Pipeline small_dam_break(scene::Solver solver, float spacing) {
    scene::Scene scene = scene::with_spacing(validation::case_scene("dam-break"), spacing, "test");
    scene.sph.solver = solver;
    frame::View view;
    view.draw = false;
    return frame::Pipeline(scene, shader::FileSource::embedded(), view);
}

}  // namespace

TEST_CASE("validation: particle snapshots are each frame's arrays, tagged, frames late", "[validation]") {
    test::context();
    test::Random rng;
    INFO("seed " << rng.seed());
    const scene::Solver solver = rng.below(2) ? scene::Solver::dfsph : scene::Solver::pbf;
    frame::Pipeline pipeline = small_dam_break(solver, rng.uniform(0.022f, 0.03f));
    sim::Fluid& fluid = pipeline.simulation()->fluid();
    // All three arrays, and a subset whose record holds velocities alone.
    struct Expect { std::vector<glm::vec4> x, d, v; };
    std::map<std::uint64_t, Expect> expect;
    std::vector<std::uint64_t> all_order, subset_order;
    int mismatches = 0;
    ParticleSnapshots all(fluid, ParticleSnapshots::kPositions | ParticleSnapshots::kDensities | ParticleSnapshots::kVelocities,
                          [&](const ParticleSnapshots::View& s) {
                              all_order.push_back(s.tag);
                              const Expect& e = expect.at(s.tag);
                              if (!same_bits(s.positions, e.x) || !same_bits(s.densities, e.d) || !same_bits(s.velocities, e.v)) ++mismatches;
                          });
    ParticleSnapshots subset(fluid, ParticleSnapshots::kVelocities, [&](const ParticleSnapshots::View& s) {
        subset_order.push_back(s.tag);
        if (!s.positions.empty() || !s.densities.empty() || !same_bits(s.velocities, expect.at(s.tag).v)) ++mismatches;
    });
    frame::FrameHooks hooks;
    hooks.after = [&](frame::Pipeline& p) {
        const std::uint64_t tag = 1000 + p.frames();
        // The reference: the same arrays, read now (the test may wait; the cases do not), before the
        // captures, which may hand over a record at once where the copy has already finished.
        expect[tag] = {fluid.positions().read<glm::vec4>(fluid.count()), fluid.densities().read<glm::vec4>(fluid.count()),
                       fluid.velocities().read<glm::vec4>(fluid.count())};
        all.capture(tag);
        subset.capture(tag);
        if (rng.below(2)) all.poll();
    };
    const int frames = 5 + int(rng.below(4));   // more than the ring is deep
    INFO(fluid.count() << " particles, " << frames << " frames, solver " << int(solver));
    REQUIRE(frame::run_frames(pipeline, std::uint64_t(frames), hooks) == std::uint64_t(frames));
    pipeline.drain();
    all.drain();
    subset.drain();
    REQUIRE(!pipeline.instability());
    CHECK(mismatches == 0);
    REQUIRE(all_order.size() == std::size_t(frames));
    REQUIRE(subset_order == all_order);
    for (int f = 0; f < frames; ++f) CHECK(all_order[std::size_t(f)] == 1000 + std::uint64_t(f) + 1);
    // The frames moved the fluid: the comparison is not of one state.
    CHECK(expect.begin()->second.x != expect.rbegin()->second.x);
    test::require_no_gl_errors();
}

TEST_CASE("validation: stop_particles zeroes every velocity and nothing else", "[validation]") {
    test::context();
    frame::Pipeline pipeline = small_dam_break(scene::Solver::dfsph, 0.025f);
    sim::Fluid& fluid = pipeline.simulation()->fluid();
    REQUIRE(frame::run_frames(pipeline, 3) == 3);
    pipeline.drain();
    const std::vector<glm::vec4> x = fluid.positions().read<glm::vec4>(fluid.count());
    const std::vector<glm::vec4> d = fluid.densities().read<glm::vec4>(fluid.count());
    bool moving = false;
    for (const glm::vec4& v : fluid.velocities().read<glm::vec4>(fluid.count())) moving = moving || glm::length(glm::vec3(v)) > 0.0f;
    REQUIRE(moving);   // the column has started to fall
    fluid.stop_particles();
    for (const glm::vec4& v : fluid.velocities().read<glm::vec4>(fluid.count())) REQUIRE(v == glm::vec4(0.0f));
    CHECK(fluid.positions().read<glm::vec4>(fluid.count()) == x);
    CHECK(fluid.densities().read<glm::vec4>(fluid.count()) == d);
    test::require_no_gl_errors();
}
