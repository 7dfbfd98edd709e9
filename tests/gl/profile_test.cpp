// Per-pass GPU timing (profile::GpuTimer) and its reports (profile/report.h). What is checked is
// the bookkeeping — which passes ran, how often, in which frame, and that every report names them —
// never the times themselves: llvmpipe's timestamps read about 0, so times are only checked ≥ 0.
#include "support/gl_fixture.h"

#include <dlfcn.h>

#include <algorithm>
#include <cstdint>
#include <map>
#include <stdexcept>
#include <sstream>
#include <string>
#include <vector>

#include "core/error.h"
#include "frame/pipeline.h"
#include "gl/faults.h"
#include "gl/gl.h"
#include "profile/gpu_timer.h"
#include "profile/report.h"
#include "scene/scene.h"
#include "shader/source.h"

using ranryu::profile::GpuTimer;
using ranryu::profile::PassSamples;

// ---- The query probe: this program's own glGetQueryObjectuiv and glGetQueryObjectui64v, which the
// linker prefers to libOpenGL's (the engine is linked in statically) and which call libOpenGL's (dlsym
// RTLD_NEXT). They pass everything through, count, and with `hold` answer GL_QUERY_RESULT_AVAILABLE
// with "not yet": a GPU that is behind, on demand, where llvmpipe's results come within moments. A
// GL_QUERY_RESULT read of a query whose result is not available is counted as a wait.
namespace {
struct QueryProbe {
    bool hold = false;
    std::uint64_t asked = 0;   // GL_QUERY_RESULT_AVAILABLE questions
    std::uint64_t reads = 0;   // GL_QUERY_RESULT reads
    std::uint64_t waits = 0;   // of those, reads of a result not available (or held): a stall in the frame path
    void reset() { *this = QueryProbe{}; }
};
QueryProbe& probe() {
    static QueryProbe p;
    return p;
}
template <class F>
F next_gl(const char* name) {
    void* f = dlsym(RTLD_NEXT, name);
    if (!f) throw std::runtime_error(std::string("profile_test: no ") + name + " after this program's own");
    return reinterpret_cast<F>(f);
}
using GetQueryUiv = void (*)(GLuint, GLenum, GLuint*);
using GetQueryUi64v = void (*)(GLuint, GLenum, GLuint64*);
GetQueryUiv real_uiv() {
    static const GetQueryUiv f = next_gl<GetQueryUiv>("glGetQueryObjectuiv");
    return f;
}
GetQueryUi64v real_ui64v() {
    static const GetQueryUi64v f = next_gl<GetQueryUi64v>("glGetQueryObjectui64v");
    return f;
}
}  // namespace

extern "C" void APIENTRY glGetQueryObjectuiv(GLuint id, GLenum pname, GLuint* params) {
    if (pname == GL_QUERY_RESULT_AVAILABLE) {
        ++probe().asked;
        if (probe().hold) {
            *params = GL_FALSE;
            return;
        }
    }
    real_uiv()(id, pname, params);
}

extern "C" void APIENTRY glGetQueryObjectui64v(GLuint id, GLenum pname, GLuint64* params) {
    if (pname == GL_QUERY_RESULT) {
        GLuint ready = GL_FALSE;
        real_uiv()(id, GL_QUERY_RESULT_AVAILABLE, &ready);
        ++probe().reads;
        if (probe().hold || !ready) ++probe().waits;
    }
    real_ui64v()(id, pname, params);
}

namespace {

const PassSamples* find_pass(const GpuTimer& t, const std::string& name) {
    for (const PassSamples& p : t.passes())
        if (p.name == name) return &p;
    return nullptr;
}

// Every frame read back against what was issued (calls_a/calls_b by frame number; b's 0 = not run):
// each sample is the pass's calls in the frame it names, the frames are distinct and in order, and
// every frame begun was either read back or counted as skipped.
void check_frames(const GpuTimer& t, ranryu::profile::PassId a, ranryu::profile::PassId b, const std::vector<int>& calls_a,
                  const std::vector<int>& calls_b, std::uint64_t frames) {
    CHECK(t.frames_begun() == frames);
    CHECK(t.frames_read() + t.skipped_frames() == frames);
    const std::vector<std::uint64_t>& numbers = t.frame_numbers();
    CHECK(std::is_sorted(numbers.begin(), numbers.end()));
    CHECK(std::adjacent_find(numbers.begin(), numbers.end()) == numbers.end());
    const PassSamples& pa = t.passes()[a.index];
    const PassSamples& pb = t.passes()[b.index];
    CHECK(pa.frames == numbers);   // "a" runs every frame
    REQUIRE(pa.calls.size() == pa.frames.size());
    REQUIRE(pa.ms.size() == pa.frames.size());
    for (std::size_t k = 0; k < pa.frames.size(); ++k) {
        REQUIRE(pa.frames[k] < frames);
        CHECK(pa.calls[k] == calls_a[std::size_t(pa.frames[k])]);
    }
    std::vector<std::uint64_t> with_b;   // the timed frames that ran "b"
    for (const std::uint64_t f : numbers)
        if (calls_b[std::size_t(f)]) with_b.push_back(f);
    CHECK(pb.frames == with_b);
    REQUIRE(pb.calls.size() == pb.frames.size());
    REQUIRE(pb.ms.size() == pb.frames.size());
    for (std::size_t k = 0; k < pb.frames.size(); ++k) CHECK(pb.calls[k] == calls_b[std::size_t(pb.frames[k])]);
}

// One frame of a bare timer: `na` calls of pass a and `nb` of b, appended to calls_a and calls_b.
void issue_frame(GpuTimer& t, ranryu::profile::PassId a, ranryu::profile::PassId b, int na, int nb, std::vector<int>& calls_a,
                 std::vector<int>& calls_b) {
    t.begin_frame();
    for (int k = 0; k < na; ++k) auto s = t.scope(a);
    for (int k = 0; k < nb; ++k) auto s = t.scope(b);
    t.end_frame();
    calls_a.push_back(na);
    calls_b.push_back(nb);
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

// Checks that exactly the passes in `expect` (name → calls per frame) have samples, one per timed frame
// of the `frames` frames (those the timer skipped, its ring full, have none), each under its frame's
// number, and that no other pass has any.
void check_samples(const GpuTimer& t, const std::map<std::string, int>& expect, std::size_t frames) {
    CHECK(t.frames_read() + t.skipped_frames() == frames);
    const std::size_t timed = t.frames_read();
    CHECK(t.frame_ms().size() == timed);
    CHECK(t.frame_numbers().size() == timed);
    CHECK(std::is_sorted(t.frame_numbers().begin(), t.frame_numbers().end()));
    CHECK(std::adjacent_find(t.frame_numbers().begin(), t.frame_numbers().end()) == t.frame_numbers().end());
    for (const double ms : t.frame_ms()) CHECK(ms >= 0.0);
    for (const auto& [name, calls] : expect) {
        INFO("pass " << name);
        const PassSamples* p = find_pass(t, name);
        REQUIRE(p != nullptr);
        CHECK(p->ms.size() == timed);
        CHECK(p->calls == std::vector<int>(timed, calls));
        CHECK(p->frames == t.frame_numbers());   // it runs every frame: a sample in each timed one
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

    // More frames than the ring is deep (6), with no drain between them: every frame comes back once,
    // in order, but for any the timer skipped because the GPU was a ring behind (counted).
    const std::size_t frames = 6 + 3 + rng.below(6);
    INFO(substeps << " substeps, " << frames << " frames");
    probe().reset();
    for (std::size_t f = 0; f < frames; ++f) run_frame(pipeline);
    CHECK(probe().waits == 0);   // the frames read only results that were available
    timer.drain();
    const std::map<std::string, int> expect = {
        {"ballistic.integrate", substeps}, {"clear", 1}, {"draw-floor", 1}, {"draw-tank", 1}, {"draw-particles", 1}};
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
    CHECK(report.frames_sampled == timer.frames_read());
    CHECK(report.frames_skipped == timer.skipped_frames());

    const std::string table = ranryu::profile::table(report);
    const nlohmann::json j = ranryu::profile::to_json(report);
    const std::string csv = ranryu::profile::to_csv(report);
    INFO(table << "\n" << j.dump(1) << "\n" << csv);
    CHECK(j.at("frames") == int(frames));
    CHECK(j.at("frames_sampled").get<std::uint64_t>() + j.at("frames_skipped").get<std::uint64_t>() == frames);
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
    CHECK(names == std::vector<std::string>{"ballistic.integrate", "clear", "draw-floor", "draw-tank", "draw-particles"});
    ranryu::test::require_no_gl_errors();
}

TEST_CASE("profile: the timer's ring hands back each frame's calls under its frame number, in order") {
    ranryu::test::context();
    ranryu::test::Random rng;
    INFO("seed " << rng.seed());
    // A ring 1..3 deep, many times more frames than that, and a different number of calls each
    // frame: every frame read back has exactly the calls issued in the frame it names. Pass "b" runs
    // only in some frames and has samples only for those. Frames the ring was full for (llvmpipe's
    // results not yet available) are skipped, never waited for, and counted.
    const int depth = 1 + int(rng.below(3));
    GpuTimer timer(depth, 16);
    const auto a = timer.pass("a"), b = timer.pass("b");
    CHECK(timer.pass("a").index == a.index);   // the same name gives the same id
    std::vector<int> calls_a, calls_b;
    const int frames = 5 * depth + 3 + int(rng.below(8));
    INFO("ring depth " << depth << ", " << frames << " frames");
    probe().reset();
    for (int f = 0; f < frames; ++f) {
        const int na = 1 + int(rng.below(8)), nb = int(rng.below(3));
        issue_frame(timer, a, b, na, nb, calls_a, calls_b);
        // At most `depth` frames are outstanding; the others came back or were skipped.
        CHECK(timer.frames_read() + timer.skipped_frames() + std::uint64_t(depth) >= std::uint64_t(f + 1));
    }
    CHECK(probe().waits == 0);   // no GL_QUERY_RESULT read of a query whose result was not available
    timer.drain();
    check_frames(timer, a, b, calls_a, calls_b, std::uint64_t(frames));
    // A second drain finds nothing new.
    const std::uint64_t read = timer.frames_read();
    timer.drain();
    CHECK(timer.frames_read() == read);
    ranryu::test::require_no_gl_errors();
}

TEST_CASE("profile: with results not yet available, many frames in a row never wait, skip once the ring is full, and are counted") {
    ranryu::test::context();
    ranryu::test::Random rng;
    INFO("seed " << rng.seed());
    const int depth = 1 + int(rng.below(6));
    GpuTimer timer(depth, 4);
    const auto a = timer.pass("a"), b = timer.pass("b");
    std::vector<int> calls_a, calls_b;
    GLint groups_before = 0, groups_after = 0;
    glGetIntegerv(GL_DEBUG_GROUP_STACK_DEPTH, &groups_before);
    auto frame = [&] {
        const int na = 1 + int(rng.below(9)), nb = int(rng.below(3));   // past the 4 expected: the pool grows
        issue_frame(timer, a, b, na, nb, calls_a, calls_b);
    };
    // The driver answers "not yet" for every query (the probe below; a GPU far behind): the first
    // `depth` frames take the ring's slots, every later one is skipped, and no result is read at all.
    const int held = depth + 1 + int(rng.below(4 * unsigned(depth) + 8));
    INFO("ring depth " << depth << ", " << held << " frames held");
    probe().reset();
    probe().hold = true;
    for (int f = 0; f < held; ++f) frame();
    probe().hold = false;
    CHECK(probe().reads == 0);
    CHECK(probe().asked > 0);              // it did ask, each frame
    CHECK(timer.frames_read() == 0);
    CHECK(timer.skipped_frames() == std::uint64_t(held - depth));
    CHECK(timer.frames_begun() == std::uint64_t(held));
    // Then the results come: the held frames are collected as they become available, later frames
    // take slots again; nothing waits until the drain.
    const int more = 2 * depth + int(rng.below(6));
    for (int f = 0; f < more; ++f) frame();
    CHECK(probe().waits == 0);
    timer.drain();
    glGetIntegerv(GL_DEBUG_GROUP_STACK_DEPTH, &groups_after);
    CHECK(groups_after == groups_before);   // skipped frames' passes open and close their groups too
    check_frames(timer, a, b, calls_a, calls_b, std::uint64_t(held + more));
    // The first `depth` frames were timed, the rest of the held ones were not.
    const auto& numbers = timer.frame_numbers();
    REQUIRE(numbers.size() >= std::size_t(depth));
    for (int f = 0; f < depth; ++f) CHECK(numbers[std::size_t(f)] == std::uint64_t(f));
    if (numbers.size() > std::size_t(depth)) CHECK(numbers[std::size_t(depth)] >= std::uint64_t(held));
    // The report says how many went untimed.
    const ranryu::profile::Report report = ranryu::profile::summarize(timer, {});
    CHECK(report.frames_skipped == timer.skipped_frames());
    CHECK_THAT(ranryu::profile::table(report), Catch::Contains(std::to_string(timer.skipped_frames()) + " frames not timed"));
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

// A pass within another (GpuTimer::pass(name, within); `ranryu profile --detail`): without detail its
// calls are counted, frame by frame, and untimed, its time its parent's; with detail it has samples of
// its own, which lie inside its parent's span, and the reports list it right under its parent, marked,
// in every format, even when it first ran frames after the passes that follow its parent. Either way it
// opens its debug group, and once it ends, a GL error is named after its parent again.
TEST_CASE("profile: a pass within another is timed apart only with detail, its calls counted either way, and reported under it") {
    ranryu::test::context();
    ranryu::test::Random rng;
    INFO("seed " << rng.seed());
    GpuTimer timer(4, 8);
    const auto first = timer.pass("first");
    const auto parent = timer.pass("parent");
    const auto child = timer.pass("child", parent);
    const auto last = timer.pass("last");
    CHECK(timer.pass("child", parent).index == child.index);   // named again within the same: the same pass
    CHECK(timer.pass("child").index == child.index);
    CHECK_THROWS_AS(timer.pass("child", first), ranryu::Error);    // within another than it was named in
    CHECK_THROWS_AS(timer.pass("first", parent), ranryu::Error);   // a pass of its own named within one
    CHECK_THROWS_AS(timer.pass("grandchild", child), ranryu::Error);   // passes nest one level
    CHECK_THROWS_AS(timer.pass("orphan", ranryu::profile::PassId{99}), ranryu::Error);
    CHECK(timer.passes()[child.index].within == int(parent.index));
    CHECK(timer.passes()[parent.index].within == -1);

    GLuint buffer = 0;
    glGenBuffers(1, &buffer);
    glBindBuffer(GL_COPY_WRITE_BUFFER, buffer);
    glBufferData(GL_COPY_WRITE_BUFFER, 1 << 16, nullptr, GL_STATIC_DRAW);
    GLint before = 0, deepest = 0, after = 0;
    glGetIntegerv(GL_DEBUG_GROUP_STACK_DEPTH, &before);
    std::string name_after_child;
    // A frame: "first" once, then "parent" around `n` calls of "child", each with some work, then "last".
    auto frame = [&](int n) {
        timer.begin_frame();
        { auto s = timer.scope(first); }
        {
            auto s = timer.scope(parent);
            for (int k = 0; k < n; ++k) {
                auto c = timer.scope(child);
                glGetIntegerv(GL_DEBUG_GROUP_STACK_DEPTH, &deepest);
                const std::uint32_t zero = 0;
                glClearBufferData(GL_COPY_WRITE_BUFFER, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
            }
            name_after_child = ranryu::gl::current_pass();
        }
        { auto s = timer.scope(last); }
        timer.end_frame();
    };
    // Six frames in a row, no drain between them: the ring of four skips some, and the counts are of
    // the frames read back only, as the timed samples are.
    std::vector<int> calls;
    for (int f = 0; f < 6; ++f) calls.push_back(1 + int(rng.below(9))), frame(calls.back());
    timer.drain();
    CHECK(deepest == before + 2);   // the child's group inside the parent's
    CHECK(name_after_child == "parent");
    CHECK(timer.passes()[child.index].ms.empty());
    std::uint64_t counted = 0;
    for (const std::uint64_t f : timer.frame_numbers()) counted += std::uint64_t(calls[std::size_t(f)]);
    CHECK(timer.untimed_calls()[child.index] == counted);
    CHECK(timer.passes()[child.index].untimed_frames == timer.frame_numbers());
    CHECK(timer.untimed_calls()[parent.index] == 0u);
    ranryu::profile::RunInfo info;
    ranryu::profile::Report r = ranryu::profile::summarize(timer, info);
    REQUIRE(r.passes.size() == 3u);
    CHECK_FALSE(r.detail);
    REQUIRE(r.untimed_within.size() == 1u);
    CHECK(r.untimed_within[0].name == "child");
    CHECK(r.untimed_within[0].within == "parent");
    CHECK(r.untimed_within[0].calls_per_frame == Approx(double(counted) / double(timer.frames_read())));
    CHECK_THAT(ranryu::profile::table(r), Catch::Contains("not apart") && Catch::Contains("child"));
    CHECK(ranryu::profile::to_json(r).at("untimed_within").at(0).at("within") == "parent");

    // With detail, after a frame in which the parent ran no child: the child's first sample comes back
    // after "last"'s, and the report still lists it under its parent.
    timer.drain();
    timer.reset_samples();
    CHECK(timer.untimed_calls()[child.index] == 0u);
    timer.set_detail(true);
    frame(0);
    timer.drain();
    calls.clear();
    for (int f = 0; f < 3; ++f) calls.push_back(1 + int(rng.below(9))), frame(calls.back()), timer.drain();
    CHECK(timer.first_use_order() == std::vector<std::uint16_t>{first.index, parent.index, last.index, child.index});
    const PassSamples& c = timer.passes()[child.index];
    CHECK(c.calls == calls);
    CHECK(timer.untimed_calls()[child.index] == 0u);
    for (std::size_t k = 0; k < c.ms.size(); ++k) CHECK(c.ms[k] <= timer.passes()[parent.index].ms[k + 1] + 1e-6);
    r = ranryu::profile::summarize(timer, info);
    CHECK(r.detail);
    CHECK(r.untimed_within.empty());
    REQUIRE(r.passes.size() == 4u);
    CHECK(r.passes[0].name == "first");
    CHECK(r.passes[1].name == "parent");
    CHECK(r.passes[2].name == "child");
    CHECK(r.passes[3].name == "last");
    CHECK(r.passes[2].within == "parent");
    CHECK(r.passes[2].calls_per_frame == Approx(double(calls[0] + calls[1] + calls[2]) / 4.0));   // over the 4 frames read
    const std::string text = ranryu::profile::table(r);
    INFO(text);
    CHECK_THAT(text, Catch::Contains("\n  child "));   // indented under its parent
    CHECK_THAT(text, Catch::Contains("--detail"));
    const nlohmann::json j = ranryu::profile::to_json(r);
    CHECK(j.at("passes").at(2).at("within") == "parent");
    CHECK_FALSE(j.at("passes").at(1).contains("within"));
    CHECK(j.at("detail") == true);
    const std::string csv = ranryu::profile::to_csv(r);
    CHECK(csv.substr(0, csv.find('\n')).ends_with(",within"));
    CHECK_THAT(csv, Catch::Contains(",child,") && Catch::Contains(",parent\n"));
    glGetIntegerv(GL_DEBUG_GROUP_STACK_DEPTH, &after);
    CHECK(after == before);
    timer.set_detail(false);
    glDeleteBuffers(1, &buffer);
    ranryu::test::require_no_gl_errors();
}
