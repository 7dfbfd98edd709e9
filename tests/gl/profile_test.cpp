// Per-pass GPU timing (profile::GpuTimer) and its reports (profile/report.h). What is checked is
// the bookkeeping — which passes ran, how often, in which frame, and that every report names them —
// never the times themselves: llvmpipe's timestamps read about 0, so times are only checked ≥ 0.
#include "support/gl_fixture.h"

#include <algorithm>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "core/error.h"
#include "frame/pipeline.h"
#include "gl/gl.h"
#include "profile/gpu_timer.h"
#include "profile/report.h"
#include "scene/scene.h"
#include "shader/source.h"

using ranryu::profile::GpuTimer;
using ranryu::profile::PassSamples;

namespace {

const PassSamples* find_pass(const GpuTimer& t, const std::string& name) {
    for (const PassSamples& p : t.passes())
        if (p.name == name) return &p;
    return nullptr;
}

// A tiny ballistic scene: 27 particles, `substeps` substeps a frame.
ranryu::scene::Scene tiny_scene(int substeps) {
    const std::string json = R"({"name": "tiny", "particles": {"spacing": 0.1, "blocks": [{"min": [0.2, 0.2, 0.2], "max": [0.5, 0.5, 0.5]}]},
                                  "time": {"frame_dt": 0.012, "substep_dt": )" + std::to_string(0.012 / substeps) + "}}";
    return ranryu::scene::parse(json, "profile_test");
}

// One frame of the pipeline, as app/commands.cpp runs it.
void run_frame(ranryu::frame::Pipeline& p) {
    p.begin_frame();
    p.simulate();
    p.draw();
    p.end_frame();
}

// Checks that exactly the passes in `expect` (name → calls per frame) have samples, one per frame
// for `frames` frames, and that no other pass has any.
void check_samples(const GpuTimer& t, const std::map<std::string, int>& expect, std::size_t frames) {
    CHECK(t.frames_read() == frames);
    CHECK(t.frame_ms().size() == frames);
    for (const double ms : t.frame_ms()) CHECK(ms >= 0.0);
    for (const auto& [name, calls] : expect) {
        INFO("pass " << name);
        const PassSamples* p = find_pass(t, name);
        REQUIRE(p != nullptr);
        CHECK(p->ms.size() == frames);
        CHECK(p->calls == std::vector<int>(frames, calls));
        for (const double ms : p->ms) CHECK(ms >= 0.0);
    }
    for (const PassSamples& p : t.passes()) {
        INFO("pass " << p.name);
        if (!expect.count(p.name)) CHECK(p.ms.empty());
    }
}

}  // namespace

TEST_CASE("profile: a pipeline's passes are timed once per call, every frame, and every report names them") {
    ranryu::test::context();
    ranryu::test::Random rng;
    INFO("seed " << rng.seed());
    const int substeps = 1 + int(rng.below(6));
    const ranryu::scene::Scene scene = tiny_scene(substeps);
    REQUIRE(scene.substeps() == substeps);
    ranryu::frame::Pipeline pipeline(scene, ranryu::shader::FileSource::embedded(), 64, 48);
    GpuTimer& timer = pipeline.timer();

    // More frames than the ring is deep (4), with no drain between them: every frame must still
    // come back once, in order.
    const std::size_t frames = 4 + 3 + rng.below(6);
    INFO(substeps << " substeps, " << frames << " frames");
    for (std::size_t f = 0; f < frames; ++f) run_frame(pipeline);
    timer.drain();
    const std::map<std::string, int> expect = {
        {"integrate", substeps}, {"clear", 1}, {"draw-floor", 1}, {"draw-tank", 1}, {"draw-particles", 1}};
    check_samples(timer, expect, frames);

    ranryu::profile::RunInfo info;
    info.renderer = "test renderer";
    info.scene = scene.name;
    info.frames = int(frames);
    info.substeps = substeps;
    const ranryu::profile::Report report = ranryu::profile::summarize(timer, info);
    REQUIRE(report.passes.size() == expect.size());
    for (const auto& row : report.passes) {
        INFO("pass " << row.name);
        REQUIRE(expect.count(row.name) == 1);
        CHECK(row.calls_per_frame == Approx(expect.at(row.name)));
        CHECK(row.min_ms >= 0.0);
        CHECK(row.min_ms <= row.median_ms);
        CHECK(row.median_ms <= row.max_ms);
        CHECK(row.share >= 0.0);
    }
    CHECK(report.frame.calls_per_frame == Approx(1.0));

    const std::string table = ranryu::profile::table(report);
    const nlohmann::json j = ranryu::profile::to_json(report);
    const std::string csv = ranryu::profile::to_csv(report);
    INFO(table << "\n" << j.dump(1) << "\n" << csv);
    CHECK(j.at("frames") == int(frames));
    CHECK(j.at("substeps_per_frame") == substeps);
    REQUIRE(j.at("passes").size() == expect.size());
    std::map<std::string, int> csv_rows;   // pass name → rows naming it (the 9th field)
    std::istringstream lines(csv);
    std::string line;
    std::getline(lines, line);
    CHECK(line.rfind("device,", 0) == 0);
    while (std::getline(lines, line)) {
        std::istringstream fields(line);
        std::string field;
        for (int k = 0; k < 9; ++k) std::getline(fields, field, ',');
        ++csv_rows[field];
    }
    for (const auto& [name, calls] : expect) {
        INFO("pass " << name);
        CHECK_THAT(table, Catch::Contains(name));
        const auto& passes = j.at("passes");
        const auto it = std::find_if(passes.begin(), passes.end(), [&](const nlohmann::json& p) { return p.at("name") == name; });
        REQUIRE(it != passes.end());
        CHECK(it->at("calls_per_frame").get<double>() == Approx(calls));
        CHECK(csv_rows[name] == 1);
    }
    CHECK(csv_rows.size() == expect.size() + 1);   // and the whole-frame row
    CHECK(csv_rows.count("frame (GPU span)") == 1);

    // reset_samples forgets the samples and keeps the names; timing then starts afresh.
    const std::size_t names = timer.passes().size();
    timer.reset_samples();
    CHECK(timer.passes().size() == names);
    check_samples(timer, {}, 0);
    const std::size_t more = 1 + rng.below(6);
    for (std::size_t f = 0; f < more; ++f) run_frame(pipeline);
    timer.drain();
    check_samples(timer, expect, more);
    ranryu::test::require_no_gl_errors();
}

// profile/report.h documents Report::passes as "in order of first use", not the order in which
// GpuTimer::pass() named them: frame::Pipeline builds the Renderer before the simulation, yet every
// frame starts with the simulation's passes.
TEST_CASE("profile: report rows follow the order in which a frame first ran the passes") {
    ranryu::test::context();
    ranryu::frame::Pipeline pipeline(tiny_scene(2), ranryu::shader::FileSource::embedded(), 32, 32);
    run_frame(pipeline);
    pipeline.timer().drain();
    const ranryu::profile::Report report = ranryu::profile::summarize(pipeline.timer(), {});
    std::vector<std::string> names;
    for (const auto& row : report.passes) names.push_back(row.name);
    CHECK(names == std::vector<std::string>{"integrate", "clear", "draw-floor", "draw-tank", "draw-particles"});
    ranryu::test::require_no_gl_errors();
}

TEST_CASE("profile: the timer's ring hands back each frame's calls in frame order") {
    ranryu::test::context();
    ranryu::test::Random rng;
    INFO("seed " << rng.seed());
    // A ring 1..3 deep, many times more frames than that, and a different number of calls each
    // frame: the per-frame call counts read back must be exactly the sequence issued. Pass "b"
    // runs only in some frames and has samples only for those.
    const int depth = 1 + int(rng.below(3));
    GpuTimer timer(depth, 16);
    const auto a = timer.pass("a"), b = timer.pass("b");
    CHECK(timer.pass("a").index == a.index);   // the same name gives the same id
    std::vector<int> calls_a, calls_b;
    const int frames = 5 * depth + 3 + int(rng.below(8));
    INFO("ring depth " << depth << ", " << frames << " frames");
    for (int f = 0; f < frames; ++f) {
        timer.begin_frame();
        const int na = 1 + int(rng.below(8)), nb = int(rng.below(3));
        for (int k = 0; k < na; ++k) auto s = timer.scope(a);
        for (int k = 0; k < nb; ++k) auto s = timer.scope(b);
        timer.end_frame();
        calls_a.push_back(na);
        if (nb) calls_b.push_back(nb);
        // Frames come back a ring behind: at most `depth` are outstanding.
        CHECK(timer.frames_read() + std::uint64_t(depth) >= std::uint64_t(f + 1));
    }
    timer.drain();
    CHECK(timer.frames_read() == std::uint64_t(frames));
    CHECK(timer.passes()[a.index].calls == calls_a);
    CHECK(timer.passes()[b.index].calls == calls_b);
    CHECK(timer.passes()[a.index].ms.size() == calls_a.size());
    CHECK(timer.passes()[b.index].ms.size() == calls_b.size());
    // A second drain finds nothing new.
    timer.drain();
    CHECK(timer.frames_read() == std::uint64_t(frames));
    ranryu::test::require_no_gl_errors();
}

TEST_CASE("profile: misuse of the timer is an error, not a silent miscount") {
    ranryu::test::context();
    GpuTimer timer(2, 3);
    const auto p = timer.pass("p");
    CHECK_THROWS_AS(timer.end_frame(), ranryu::Error);
    timer.begin_frame();
    CHECK_THROWS_AS(timer.begin_frame(), ranryu::Error);
    for (int k = 0; k < 3; ++k) auto s = timer.scope(p);
    timer.end_frame();
    timer.drain();
    CHECK(timer.passes()[p.index].calls == std::vector<int>{3});
    ranryu::test::require_no_gl_errors();
}

// A GpuTimer::Scope whose begin() throws (outside a frame) must not leave a KHR_debug group pushed:
// the destructor of a Scope whose constructor threw never runs, so Scope::Scope calls begin() before
// it pushes the group (engine/profile/gpu_timer.cpp). A frame past the expected number of passes
// grows the query pool instead of failing, and every call is still timed.
TEST_CASE("profile: a pass that throws leaves the debug-group stack as it found it") {
    ranryu::test::context();
    GpuTimer timer(2, 2);
    const auto p = timer.pass("p");
    GLint before = 0, after = 0;
    glGetIntegerv(GL_DEBUG_GROUP_STACK_DEPTH, &before);
    CHECK_THROWS_AS(timer.scope(p), ranryu::Error);   // outside a frame
    timer.begin_frame();
    for (int k = 0; k < 9; ++k) auto s = timer.scope(p);   // past the 2 expected: the pool grows
    timer.end_frame();
    glGetIntegerv(GL_DEBUG_GROUP_STACK_DEPTH, &after);
    CHECK(after == before);
    timer.drain();
    CHECK(timer.passes()[p.index].calls == std::vector<int>{9});
    while (after-- > before) glPopDebugGroup();   // leave the shared context as the next case expects
    ranryu::test::require_no_gl_errors();
}
