// validation::CompressionMeter, the scene cases' per-frame mean compression computed on the GPU and
// read back asynchronously, against the CPU's sum in double of the same densities read back
// synchronously (what scene_run did before). Tolerance: 1e-5 of the mean, relative (the float
// reduction's bound, glsl/validation/mean_compression.comp), plus 1e-12 absolute for a mean of 0.
#include "support/gl_fixture.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <vector>

#include <glm/glm.hpp>

#include "frame/loop.h"
#include "frame/pipeline.h"
#include "gl/objects.h"
#include "profile/gpu_timer.h"
#include "scene/scene.h"
#include "shader/source.h"
#include "sim/simulation.h"
#include "validation/cases.h"

using namespace ranryu;

namespace {

// (1/n)·Σ max(ρ/ρ0 − 1, 0) in double, as scene_run computed it on the CPU.
double cpu_mean_compression(const std::vector<glm::vec4>& d, double rest) {
    double excess = 0.0;
    for (const glm::vec4& di : d) excess += std::max(double(di.x) / rest - 1.0, 0.0);
    return excess / double(std::max<std::size_t>(d.size(), 1));
}

void check_close(double gpu, double cpu) {
    INFO("GPU " << gpu << ", CPU " << cpu);
    CHECK(std::abs(gpu - cpu) <= 1e-5 * std::abs(cpu) + 1e-12);
}

}  // namespace

TEST_CASE("validation: the GPU's mean compression equals the CPU's of the same densities, tagged, frames late") {
    test::context();
    test::Random rng;
    INFO("seed " << rng.seed());
    // Counts below one workgroup, across several, and past 1024 groups of 256 (the first pass's
    // threads then add more than one particle each).
    const std::size_t counts[] = {1 + rng.below(255), 257 + rng.below(20000), 262144 + 1 + rng.below(150000)};
    for (const std::size_t n : counts) {
        const float rest = rng.uniform(500.0f, 2000.0f);
        INFO(n << " particles, rho0 " << rest);
        std::map<std::uint64_t, double> got;
        std::vector<std::uint64_t> order;
        profile::GpuTimer timer(4, 64);
        validation::CompressionMeter meter(shader::FileSource::embedded(), timer, n, rest, [&](std::uint64_t tag, double mean) {
            order.push_back(tag);
            got[tag] = mean;
        });
        // More measurements than the readback ring is deep, none polled: fresh densities each time
        // (some parked at 0, some below rho0, most above), each uploaded after the last was queued,
        // each into its own buffer, as the simulation's densities are written (by the GPU) after the
        // last measurement was queued: NVIDIA's driver (580) moves a buffer the CPU both writes and
        // reads into host memory and then lets an upload overtake a dispatch queued before it
        // (docs/PERFORMANCE.md "A buffer the CPU reads, and the GL tests on the H200"), which a test reusing
        // one buffer would measure.
        const int measures = 2 * validation::CompressionMeter::kDepth + 3;
        std::vector<gl::Buffer> buffers;
        for (int m = 0; m < measures; ++m) buffers.emplace_back(n * sizeof(glm::vec4), GL_DYNAMIC_COPY, nullptr, "test.densities");
        std::vector<double> expect;
        for (int m = 0; m < measures; ++m) {
            gl::Buffer& densities = buffers[std::size_t(m)];
            std::vector<glm::vec4> d(n);
            const bool none_above = m == 1;   // one measurement whose compression is exactly 0
            for (glm::vec4& di : d) {
                const unsigned kind = rng.below(10);
                const float rho = kind == 0 ? 0.0f
                                  : kind < 4 || none_above ? rng.uniform(0.5f, 1.0f) * rest
                                                           : rng.uniform(1.0f, 1.0f + (m % 3 == 0 ? 0.002f : 0.3f)) * rest;
                di = glm::vec4(rho, rng.uniform(-1.0f, 1.0f), 0.0f, 0.0f);   // y: a field the meter must not read
            }
            densities.upload(d.data(), d.size() * sizeof(glm::vec4));
            expect.push_back(cpu_mean_compression(densities.read<glm::vec4>(n), double(rest)));
            timer.begin_frame();
            meter.measure(densities, 100 + std::uint64_t(m));
            timer.end_frame();
        }
        meter.drain();
        timer.drain();
        // Its two dispatches named within its pass (not timed apart without detail): one call each a measurement.
        const profile::PassId parent = timer.pass("mean-compression");
        const std::vector<std::uint64_t> calls = timer.untimed_calls();
        CHECK(calls.at(timer.pass("mean-compression.partials", parent).index) == std::uint64_t(measures));
        CHECK(calls.at(timer.pass("mean-compression.total", parent).index) == std::uint64_t(measures));
        REQUIRE(order.size() == std::size_t(measures));
        for (int m = 0; m < measures; ++m) {
            INFO("measurement " << m);
            CHECK(order[std::size_t(m)] == 100 + std::uint64_t(m));   // oldest first, each under its own tag
            check_close(got.at(100 + std::uint64_t(m)), expect[std::size_t(m)]);
        }
        CHECK(got.at(101) == 0.0);
        CHECK(meter.drain() == 0);   // nothing left
    }
    test::require_no_gl_errors();
}

// In the frame loop as scene_run uses it, with PBF: the value that comes back for frame f is the
// mean compression of the densities at the end of frame f, those of its last step's last iteration,
// which the test reads back synchronously after the frame (the CPU's computation before the change).
TEST_CASE("validation: scene_run's per-frame compression is that of each frame's final PBF densities", "[pbf]") {
    test::context();
    test::Random rng;
    INFO("seed " << rng.seed());
    scene::Scene scene = scene::with_spacing(validation::case_scene("dam-break"), 0.025f, "test");
    scene.sph.solver = scene::Solver::pbf;
    frame::View view;
    view.draw = false;
    frame::Pipeline pipeline(scene, shader::FileSource::embedded(), view);
    sim::Fluid& fluid = pipeline.simulation()->fluid();
    std::map<std::uint64_t, double> gpu, cpu;
    validation::CompressionMeter meter(shader::FileSource::embedded(), pipeline.timer(), fluid.count(), scene.sph.rest_density,
                                       [&](std::uint64_t frame, double c) { gpu[frame] = c; });
    frame::FrameHooks hooks;
    hooks.after_draw = [&](frame::Pipeline& p) { meter.measure(fluid.densities(), p.frames()); };
    hooks.after = [&](frame::Pipeline& p) {
        meter.poll();
        cpu[p.frames() - 1] = cpu_mean_compression(fluid.densities().read<glm::vec4>(fluid.count()), scene.sph.rest_density);
    };
    const int frames = 4 + int(rng.below(4));
    INFO(fluid.count() << " particles, " << frames << " frames");
    REQUIRE(frame::run_frames(pipeline, std::uint64_t(frames), hooks) == std::uint64_t(frames));
    pipeline.drain();
    meter.drain();
    REQUIRE(!pipeline.instability());
    REQUIRE(gpu.size() == std::size_t(frames));
    REQUIRE(cpu.size() == std::size_t(frames));
    double most = 0.0;
    for (const auto& [f, c] : cpu) {
        INFO("frame " << f);
        check_close(gpu.at(f), c);
        most = std::max(most, c);
    }
    CHECK(most > 0.0);   // the column's weight compresses it: the comparison is not of zeros

    // scene_run itself: its fields from the same values (a fresh run, so only their relations).
    const double frame_dt = double(scene.frame_dt);
    const validation::SceneRunResult r = validation::scene_run(scene, shader::FileSource::embedded(), frames * frame_dt);
    CHECK(r.frames == frames);
    CHECK(r.peak_mean_compression >= r.average_mean_compression);
    CHECK(r.average_mean_compression > 0.0);
    CHECK(r.peak_time > 0.0);
    CHECK(r.peak_time <= frames * frame_dt * (1.0 + 1e-9));
    CHECK(std::abs(std::remainder(r.peak_time / frame_dt, 1.0)) < 1e-6);   // a whole frame's end
    test::require_no_gl_errors();
}

