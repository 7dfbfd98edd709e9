// frame/checkpoint.h: a run written out after some frames and read back into a fresh pipeline goes
// on exactly as the run that wrote it, and as a run never stopped: the same positions and velocities,
// to the bit, frames later, with every solver, with the turbulence force (whose sub-particles keep
// nothing between frames), and for the ballistic model. The run that wrote the checkpoint drained its
// records there, the unstopped one did not: each frame is planned from the record plan_lag() frames back
// (sim/fluid.h planning_record()), which the checkpoint carries. A part of the state that persist()
// left out (a warm start, the step's clock, a carried array, a planning record) parts the runs within a
// frame, so bit equality is what shows the list complete. And the checks: an entry of another size or
// name, a truncated file, another build's file.
#include "support/gl_fixture.h"

#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "frame/checkpoint.h"
#include "frame/loop.h"
#include "frame/pipeline.h"
#include "scene/scene.h"
#include "shader/source.h"
#include "sim/fluid.h"

using namespace ranryu;

namespace {

struct State {
    std::vector<glm::vec4> x, v;
};

State state_of(const frame::Pipeline& p) {
    return {p.positions().read<glm::vec4>(p.particle_count()), p.velocities().read<glm::vec4>(p.particle_count())};
}

bool same_bits(const std::vector<glm::vec4>& a, const std::vector<glm::vec4>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(glm::vec4)) == 0;
}

// Draws nothing: the state is what is compared (a frame's drawing reads it and writes none of it).
frame::Pipeline pipeline_of(const scene::Scene& s) {
    frame::View view;
    view.draw = false;
    return frame::Pipeline(s, shader::FileSource::embedded(), view);
}

void run(frame::Pipeline& p, std::uint64_t frames) {
    frame::run_frames(p, frames);
    p.drain();
    p.poll();
}

std::filesystem::path temp_file(const std::string& name) {
    return std::filesystem::temp_directory_path() / ("ranryu-checkpoint-" + std::to_string(::getpid()) + "-" + name);
}

}  // namespace

TEST_CASE("checkpoint: a run resumed from its checkpoint goes on as the run that wrote it and as one never stopped, to the bit",
          "[checkpoint]") {
    test::context();
    test::Random rng;
    INFO("seed " << rng.seed());
    struct Case {
        const char* scene;
        scene::Solver solver;
    };
    // Every solver over the dam break, the jet with its turbulence force and sub-particles, and the
    // ballistic block: coarse spacings, a few frames (llvmpipe).
    const Case cases[] = {{"dam-break", scene::Solver::dfsph}, {"dam-break", scene::Solver::wcsph}, {"dam-break", scene::Solver::pbf},
                          {"turbulent-jet", rng.below(2) ? scene::Solver::dfsph : scene::Solver::pbf}, {"falling-block", scene::Solver::dfsph}};
    for (const Case& c : cases) {
        scene::Scene s = scene::load(c.scene);
        if (s.model == scene::Model::sph) {
            s = scene::with_spacing(s, s.spacing * rng.uniform(1.6f, 2.2f), "test");
            s.sph.solver = c.solver;
        }
        // More frames after the checkpoint than the plan's lag, so that the resumed run plans frames from
        // records of the stopped run's (which the checkpoint carries) and then from its own.
        const std::uint64_t before = 2 + rng.below(3), after = sim::Fluid::most_plan_lag + 1 + rng.below(2);
        INFO(c.scene << " with " << scene::solver_name(c.solver) << " at " << s.spacing << " m: " << before << " frames, then " << after);
        const std::filesystem::path file = temp_file(std::string(c.scene) + ".bin");

        frame::Pipeline a = pipeline_of(s);
        run(a, before);
        frame::write_checkpoint(a, file, "test", "build A");
        const double time_at = a.simulated_time();
        run(a, after);
        const State expect = state_of(a);

        const frame::CheckpointInfo info = frame::read_checkpoint(file, "test", "build A");
        CHECK(info.frame == before);
        CHECK(info.time == time_at);
        CHECK(info.particles == a.particle_count());
        CHECK(info.scene.spacing == s.spacing);
        CHECK(info.scene.sph.solver == s.sph.solver);
        frame::Pipeline b = pipeline_of(info.scene);
        frame::load_checkpoint(b, file, "test");
        CHECK(b.frames() == before);
        run(b, after);
        CHECK(b.frames() == before + after);
        const State got = state_of(b);
        CHECK(same_bits(got.x, expect.x));
        CHECK(same_bits(got.v, expect.v));
        CHECK(b.simulated_time() == a.simulated_time());

        // A run never stopped nor drained, as far, its records handed over as late as the readback ring
        // allows: the same run.
        frame::Pipeline straight = pipeline_of(s);
        if (straight.simulation()) straight.simulation()->fluid().hand_over_records_late(true);
        frame::run_frames(straight, before + after);
        straight.drain();
        const State unstopped = state_of(straight);
        CHECK(same_bits(unstopped.x, expect.x));
        CHECK(same_bits(unstopped.v, expect.v));

        // Against a control: the same scene from its start, run as far, is elsewhere (the test sees
        // the state it compares move).
        frame::Pipeline fresh = pipeline_of(s);
        run(fresh, after);
        CHECK_FALSE(same_bits(state_of(fresh).x, expect.x));
        std::filesystem::remove(file);
    }
    test::require_no_gl_errors();
}

TEST_CASE("checkpoint: a file of another run, a damaged file, a pipeline already run: one message each", "[checkpoint]") {
    test::context();
    scene::Scene s = scene::with_spacing(scene::load("dam-break"), 0.025f, "test");
    s.sph.solver = scene::Solver::dfsph;
    const std::filesystem::path file = temp_file("errors.bin");
    {
        frame::Pipeline a = pipeline_of(s);
        run(a, 1);
        frame::write_checkpoint(a, file, "--checkpoint F", "build A");
    }
    // Loaded into a pipeline of another solver: entries it has not (PBF's carried step start) or
    // that belong to nothing there (DFSPH's).
    for (const scene::Solver solver : {scene::Solver::pbf, scene::Solver::wcsph}) {
        scene::Scene other = s;
        other.sph.solver = solver;
        frame::Pipeline b = pipeline_of(other);
        CHECK_THROWS_WITH(frame::load_checkpoint(b, file, "--resume F"),
                          Catch::Contains("--resume F") && Catch::Contains("another scene, spacing or solver"));
    }
    // Another spacing: the particle arrays are of another size.
    {
        frame::Pipeline b = pipeline_of(scene::with_spacing(s, 0.03f, "test"));
        CHECK_THROWS_WITH(frame::load_checkpoint(b, file, "--resume F"), Catch::Contains("bytes where this run has"));
    }
    // A resumed pipeline that has run no frame yet (a run stopped during its start-up) can write its
    // checkpoint again: what it loaded was sound.
    {
        frame::Pipeline b = pipeline_of(s);
        frame::load_checkpoint(b, file, "--resume F");
        CHECK(b.first_frame() == 1);
        const std::filesystem::path again = temp_file("again.bin");
        CHECK_NOTHROW(frame::write_checkpoint(b, again, "--checkpoint G", "build A"));
        CHECK(frame::read_checkpoint(again, "--resume G", "build A").frame == 1);
        std::filesystem::remove(again);
    }
    // A pipeline that has run frames.
    {
        frame::Pipeline b = pipeline_of(s);
        run(b, 1);
        CHECK_THROWS(frame::load_checkpoint(b, file, "--resume F"));
    }
    // Planning records that do not cover the frame before the last (their tags overwritten with "none"):
    // the run could not plan its next frame as the stopped run would have.
    {
        const std::filesystem::path damaged = temp_file("damaged.bin");
        std::filesystem::copy_file(file, damaged, std::filesystem::copy_options::overwrite_existing);
        std::fstream io(damaged, std::ios::in | std::ios::out | std::ios::binary);
        char magic[8];
        std::uint32_t format = 0;
        std::uint64_t length = 0;
        io.read(magic, 8).read(reinterpret_cast<char*>(&format), 4).read(reinterpret_cast<char*>(&length), 8);
        std::string header(length, '\0');
        io.read(header.data(), std::streamsize(length));
        std::uint64_t at = 20 + length, bytes = 0;
        const nlohmann::json parsed = nlohmann::json::parse(header);
        for (const auto& e : parsed["entries"]) {
            if (e["name"] == "fluid.planning_records_opened") {
                bytes = e["bytes"].get<std::uint64_t>();
                break;
            }
            at += e["bytes"].get<std::uint64_t>();
        }
        REQUIRE(bytes == sim::Fluid::most_plan_lag * sizeof(std::uint64_t));
        const std::string none(bytes, '\xFF');
        io.seekp(std::streamoff(at)).write(none.data(), std::streamsize(bytes));
        io.close();
        frame::Pipeline b = pipeline_of(s);
        CHECK_THROWS_WITH(frame::load_checkpoint(b, damaged, "--resume F"),
                          Catch::Contains("--resume F: its planning records do not cover"));
        std::filesystem::remove(damaged);
    }
    // A run whose records are not all back (handed over as late as the ring allows) is saved whole:
    // write_checkpoint() drains them first, the next frames' planning records among them.
    {
        frame::Pipeline b = pipeline_of(s);
        b.simulation()->fluid().hand_over_records_late(true);
        frame::run_frames(b, 2);
        const std::filesystem::path early = temp_file("early.bin");
        CHECK_NOTHROW(frame::write_checkpoint(b, early, "--checkpoint E", "build A"));
        frame::Pipeline c = pipeline_of(s);
        CHECK_NOTHROW(frame::load_checkpoint(c, early, "--resume E"));
        CHECK(c.first_frame() == 2);
        std::filesystem::remove(early);
    }
    // Another build's reader refuses it, naming both builds.
    CHECK_THROWS_WITH(frame::read_checkpoint(file, "--resume F", "build B"),
                      Catch::Contains("--resume F: written by ranryu build A, and this is build B"));
    // Truncated by a byte, and cut inside its header.
    const auto size = std::filesystem::file_size(file);
    std::filesystem::resize_file(file, size - 1);
    CHECK_THROWS_WITH(frame::read_checkpoint(file, "--resume F", "build A"), Catch::Contains("truncated or damaged"));
    std::filesystem::resize_file(file, 30);
    CHECK_THROWS_WITH(frame::read_checkpoint(file, "--resume F", "build A"), Catch::Contains("truncated header"));
    std::filesystem::remove(file);
    CHECK_THROWS_WITH(frame::read_checkpoint(file, "--resume F", "build A"), Catch::Contains("no such file"));
    test::require_no_gl_errors();
}
