#include "validation/cases.h"

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstring>
#include <functional>
#include <numbers>
#include <span>
#include <sstream>

#include "core/error.h"
#include "frame/loop.h"
#include "frame/pipeline.h"
#include "frame/progress.h"
#include "frame/stop.h"
#include "sim/fluid.h"
#include "sim/simulation.h"
#include "validation/snapshots.h"

namespace ranryu::validation {
namespace {

// (T, Z) pairs of a two-column CSV with optional '#' comments and a header line.
std::vector<std::pair<double, double>> read_series(const std::string& text) {
    std::vector<std::pair<double, double>> out;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) {
        if (line.empty() || line[0] == '#') continue;
        double t = 0.0, z = 0.0;
        char comma = 0;
        std::istringstream row(line);
        if (row >> t >> comma >> z && comma == ',') out.emplace_back(t, z);
    }
    return out;
}

// Linear interpolation of a series sorted by its first member; nothing outside its range.
std::optional<double> interpolate(const std::vector<std::pair<double, double>>& s, double t) {
    if (s.size() < 2 || t < s.front().first || t > s.back().first) return std::nullopt;
    const auto hi = std::lower_bound(s.begin(), s.end(), t, [](const auto& p, double v) { return p.first < v; });
    if (hi == s.begin()) return hi->second;
    const auto lo = hi - 1;
    const double w = (t - lo->first) / std::max(hi->first - lo->first, 1e-12);
    return lo->second + w * (hi->second - lo->second);
}

// A pipeline that simulates and draws nothing: the frame loop of every command, without a view.
frame::Pipeline simulation_only(const scene::Scene& scene, const shader::FileSource& shaders) {
    frame::View view;
    view.draw = false;
    return frame::Pipeline(scene, shaders, view);
}

// Runs `frames` frames of the shared frame loop with `hooks` and waits for their records. Throws
// UnstableError, or frame::interrupted() when a signal cut the frames short.
void run_with(frame::Pipeline& pipeline, int frames, const frame::FrameHooks& hooks) {
    const std::uint64_t ran = frame::run_frames(pipeline, std::uint64_t(frames), hooks);
    pipeline.drain();
    if (const auto& bad = pipeline.instability()) throw sim::UnstableError(*bad);
    if (ran < std::uint64_t(frames) && frame::stop_requested()) throw frame::interrupted(pipeline.frames());
}

// Runs `frames` frames as run_with() does (with the progress line's hooks, when there is one) and
// observes each without stopping it: after each frame it captures `snapshots`, tagged with the count
// of frames this call ran (1, 2, ...), calls `between` when there is one (the relaxation stops the
// particles there, after the capture), and polls; before each frame it asks `keep_going` too, when
// there is one. Drains the snapshots at the end and returns the frames run.
int run_observed(frame::Pipeline& pipeline, int frames, frame::Progress* progress, ParticleSnapshots& snapshots,
                 std::function<void()> between = {}, std::function<bool(const frame::Pipeline&)> keep_going = {}) {
    int ran = 0;
    frame::FrameHooks hooks = progress ? progress->hooks() : frame::FrameHooks{};
    hooks.after = [&, first = std::move(hooks.after)](frame::Pipeline& p) {
        if (first) first(p);
        snapshots.capture(std::uint64_t(++ran));
        if (between) between();
        snapshots.poll();
    };
    if (keep_going)
        hooks.keep_going = [first = std::move(hooks.keep_going), keep_going = std::move(keep_going)](const frame::Pipeline& p) {
            return (!first || first(p)) && keep_going(p);
        };
    run_with(pipeline, frames, hooks);
    snapshots.drain();
    return ran;
}

// run_with() with the progress line's hooks only.
void run(frame::Pipeline& pipeline, int frames, frame::Progress* progress) {
    run_with(pipeline, frames, progress ? progress->hooks() : frame::FrameHooks{});
}

// E of RunStats over the fluid's particles, read back (a validation run, not the frame path).
double energy(const sim::Fluid& fluid, const scene::Scene& scene) {
    const std::vector<glm::vec4> x = fluid.positions().read<glm::vec4>(fluid.count());
    const std::vector<glm::vec4> v = fluid.velocities().read<glm::vec4>(fluid.count());
    const double g = glm::length(scene.gravity);
    double e = 0.0;
    for (std::size_t i = 0; i < x.size(); ++i) e += 0.5 * double(glm::dot(glm::vec3(v[i]), glm::vec3(v[i]))) + g * (double(x[i].y) - scene.tank_min.y);
    return e;
}

// The compression now: mean over the fluid's particles of max(rho/rho0 - 1, 0), read back (a
// validation run, not the frame path).
double mean_compression(const sim::Fluid& fluid, const scene::Scene& scene) {
    const std::vector<glm::vec4> d = fluid.densities().read<glm::vec4>(fluid.count());
    double excess = 0.0;
    for (const glm::vec4& di : d) excess += std::max(double(di.x) / scene.sph.rest_density - 1.0, 0.0);
    return excess / double(std::max<std::size_t>(d.size(), 1));
}

// RunStats around one case's frames: begin() before the first, record() from the case's record
// sink, end() after the last frame has been drained.
class StatsTally {
public:
    StatsTally(const scene::Scene& scene, frame::Pipeline& pipeline) : scene_(scene), pipeline_(pipeline) {
        stats_.energy_start = energy(pipeline.simulation()->fluid(), scene);
    }
    // The fluid's records into this tally, and the solver's steps into `steps`: the record sink of a
    // case that reads nothing else from them. `steps` outlives the run.
    void listen(sim::Fluid& fluid, std::uint64_t& steps) {
        fluid.set_record_sink([this, &steps](const gpu::StepState& s) {
            record(s);
            steps += s.frame_substeps;
        });
    }
    void record(const gpu::StepState& s) {
        stats_.max_density_deviation = std::max(stats_.max_density_deviation, double(std::bit_cast<float>(s.frame_max_density)) - 1.0);
        stats_.simulated_seconds = double(s.time);
    }
    RunStats end() {
        const sim::Fluid& fluid = pipeline_.simulation()->fluid();
        stats_.mean_density_deviation = mean_compression(fluid, scene_);
        stats_.energy_end = energy(fluid, scene_);
        stats_.energy_drift = stats_.energy_start > 0.0 ? (stats_.energy_end - stats_.energy_start) / stats_.energy_start : 0.0;
        const profile::GpuTimer& timer = pipeline_.timer();
        pipeline_.timer().drain();
        for (double ms : timer.frame_ms()) stats_.gpu_ms += ms;
        // Frames the timer skipped (its ring full: GpuTimer never waits) count at the timed frames' mean.
        if (timer.skipped_frames() && timer.frames_read())
            stats_.gpu_ms *= double(timer.frames_read() + timer.skipped_frames()) / double(timer.frames_read());
        stats_.gpu_ms_per_simulated_second = stats_.simulated_seconds > 0.0 ? stats_.gpu_ms / stats_.simulated_seconds : 0.0;
        stats_.guard_spikes = fluid.guard().spikes();
        return stats_;
    }

private:
    const scene::Scene& scene_;
    frame::Pipeline& pipeline_;
    RunStats stats_;
};

// The rms and the largest speed of a velocity read-back (m/s).
struct Speeds {
    double rms = 0.0, max = 0.0;
};
Speeds speeds(std::span<const glm::vec4> v) {
    Speeds out;
    double v2 = 0.0;
    for (const glm::vec4& u : v) {
        const double speed = glm::length(glm::vec3(u));
        v2 += speed * speed;
        out.max = std::max(out.max, speed);
    }
    out.rms = std::sqrt(v2 / double(std::max<std::size_t>(v.size(), 1)));
    return out;
}

// hydrostatic_relaxation(): at most this long of frames, and the bound on a frame's rms speed from
// rest as a part of g frame_dt (cases.h, docs/VALIDATION.md "The relaxed start").
constexpr double kRelaxSeconds = 2.0;
constexpr double kRelaxAcceleration = 0.01;

}  // namespace

CompressionMeter::CompressionMeter(const shader::FileSource& shaders, profile::GpuTimer& timer, std::size_t count, float rest_density,
                                   Consumer on_value)
    : timer_(timer),
      pass_(timer.pass("mean-compression")),
      partials_pass_(timer.pass("mean-compression.partials", pass_)),
      total_pass_(timer.pass("mean-compression.total", pass_)),
      count_(count),
      groups_(std::uint32_t(std::clamp<std::size_t>((count + 255) / 256, 1, 1024))),
      on_value_(std::move(on_value)),
      partials_(shader::Program::compute(shaders, "validation/mean_compression.comp")),
      total_(shader::Program::compute(shaders, "validation/mean_compression.comp", "#define TOTAL 1\n")),
      partial_sums_(groups_ * sizeof(float), GL_DYNAMIC_COPY, nullptr, "compression.partials"),
      total_sum_(sizeof(glm::vec4), GL_DYNAMIC_COPY, nullptr, "compression.total"),
      readback_(sizeof(glm::vec4), kDepth, "compression.readback", [this](std::uint64_t tag, const void* bytes) {
          float sum = 0.0f;
          std::memcpy(&sum, bytes, sizeof sum);
          if (on_value_) on_value_(tag, double(sum) / double(std::max<std::size_t>(count_, 1)));
      }) {
    glProgramUniform1ui(partials_.id(), 0, GLuint(count_));
    glProgramUniform1f(partials_.id(), 1, rest_density);
    glProgramUniform1ui(total_.id(), 0, GLuint(groups_));
}

void CompressionMeter::measure(const gl::Buffer& densities, std::uint64_t tag) {
    auto pass = timer_.scope(pass_);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);   // the densities the passes before wrote
    {
        auto within = timer_.scope(partials_pass_);
        partials_.bind({{"Densities", &densities}, {"Partials", &partial_sums_}}).dispatch(std::size_t(groups_) * 256u);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
    {
        auto within = timer_.scope(total_pass_);
        total_.bind({{"Partials", &partial_sums_}, {"Total", &total_sum_}}).dispatch(256);
    }
    readback_.copy(total_sum_, 0, tag);   // with the barrier the copy needs
}

std::size_t CompressionMeter::poll() { return readback_.poll(); }
std::size_t CompressionMeter::drain() { return readback_.drain(); }

DamBreakResult dam_break(const scene::Scene& scene, const shader::FileSource& shaders, frame::Progress* progress) {
    if (scene.model != scene::Model::sph || scene.blocks.empty()) throw InputError("dam-break: the scene must be SPH with one block");
    const scene::Block& column = scene.blocks.front();
    DamBreakResult r;
    r.a = column.max.x - column.min.x;
    r.wall = scene.tank_min.x;
    r.spacing = scene.spacing;
    const double g = glm::length(scene.gravity);
    const double time_scale = std::sqrt(2.0 * g / r.a);   // T = t * sqrt(2 g / a)
    const auto data = read_series(scene::bundled_file("validation/martin-moyce-1952-surge-front.csv"));
    const double t_end = (data.back().first + 0.1) / time_scale;
    const int frames = int(std::ceil(t_end / scene.frame_dt)) + 1;

    frame::Pipeline pipeline = simulation_only(scene, shaders);
    sim::Fluid& fluid = pipeline.simulation()->fluid();
    r.particles = fluid.count();
    const float origin_x = fluid.params().domain_min.x;
    r.simulated.emplace_back(0.0, 1.0);   // the column's edge at t = 0
    StatsTally tally(scene, pipeline);
    fluid.set_record_sink([&](const gpu::StepState& s) {
        tally.record(s);
        const double front = double(origin_x) + std::bit_cast<float>(s.front);
        r.simulated.emplace_back(double(s.time) * time_scale, (front - r.wall) / r.a);
        r.steps += s.frame_substeps;
    });
    if (progress) progress->expect(std::uint64_t(frames));
    const auto start = std::chrono::steady_clock::now();
    run(pipeline, frames, progress);
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    r.stats = tally.end();

    double sum2 = 0.0;
    for (const auto& [t, z] : data) {
        const auto zs = interpolate(r.simulated, t);
        if (!zs) continue;
        r.compared.push_back({t, z, *zs});
        sum2 += (*zs - z) * (*zs - z);
        r.max_error = std::max(r.max_error, std::abs(*zs - z));
    }
    if (r.compared.empty()) throw Error("dam-break: the run covered none of the experiment's times");
    r.rms_error = std::sqrt(sum2 / double(r.compared.size()));
    return r;
}

Relaxation hydrostatic_relaxation(const scene::Scene& scene) {
    Relaxation relax;
    relax.max_frames = int(std::ceil(kRelaxSeconds / scene.frame_dt));
    relax.rms_speed = kRelaxAcceleration * double(glm::length(scene.gravity)) * scene.frame_dt;
    return relax;
}

HydrostaticResult hydrostatic(const scene::Scene& scene, const shader::FileSource& shaders, double settle_s,
                              frame::Progress* progress) {
    return hydrostatic(scene, shaders, settle_s, Relaxation{}, progress);
}

HydrostaticResult hydrostatic(const scene::Scene& scene, const shader::FileSource& shaders, double settle_s,
                              const Relaxation& relaxation, frame::Progress* progress, double average_s) {
    if (scene.model != scene::Model::sph || scene.blocks.size() != 1) throw InputError("hydrostatic: the scene must be SPH with one block");
    HydrostaticResult r;
    // H is the depth of the lattice that fills the block, whole layers of dx (the top layer's centre
    // plus half a spacing), so the reference and the fluid have one depth: a block height that is not
    // a whole number of spacings (0.25 m at 0.02 m: 12 layers, 0.24 m) would put the reference half a
    // layer's weight above the column.
    double top = scene.tank_min.y;
    for (const glm::vec4& x : scene.initial_positions()) top = std::max(top, double(x.y) + 0.5 * scene.spacing);
    r.height = top - scene.tank_min.y;
    r.spacing = scene.spacing;
    std::vector<glm::vec4> relaxed;   // the relaxed positions, empty for the lattice start
    if (relaxation.max_frames > 0) {
        // Relaxation's contract (cases.h): each frame from rest, its speeds and positions recorded, its
        // velocities zeroed; the snapshots come back frames late, so the frames stop a few after the one
        // that met the bound, and the start is that frame's.
        const auto start = std::chrono::steady_clock::now();
        frame::Pipeline settling = simulation_only(scene, shaders);
        sim::Fluid& fluid = settling.simulation()->fluid();
        std::vector<std::uint64_t> steps;   // each frame's, in frame order (one record a frame)
        fluid.set_record_sink([&](const gpu::StepState& s) { steps.push_back(s.frame_substeps); });
        if (progress) progress->expect(std::uint64_t(relaxation.max_frames));
        r.relax_rms_speeds.reserve(std::size_t(relaxation.max_frames));
        ParticleSnapshots snapshots(fluid, ParticleSnapshots::kPositions | ParticleSnapshots::kVelocities, [&](const ParticleSnapshots::View& s) {
            if (r.relaxed) return;   // a frame after the one that met the bound
            const Speeds now = speeds(s.velocities);
            r.relax_rms_speeds.push_back(now.rms);
            r.relax_max_speed = now.max;
            // The first frame starts from the lattice, not from a relaxed state: it never ends it.
            if (s.tag > 1 && now.rms <= relaxation.rms_speed) {
                r.relaxed = true;
                relaxed.assign(s.positions.begin(), s.positions.end());
            }
        });
        snapshots.hand_over_late(relaxation.late_snapshots);
        const int ran = run_observed(settling, relaxation.max_frames, progress, snapshots, [&] { fluid.stop_particles(); },
                                     [&](const frame::Pipeline&) { return !r.relaxed; });
        r.relax_frames = int(r.relax_rms_speeds.size());   // the frame that met the bound, or all that ran
        if (!r.relaxed) relaxed = fluid.positions().read<glm::vec4>(fluid.count());   // once, at rest after the last frame
        if (std::size_t(ran) != steps.size() || r.relax_frames > ran) throw Error("hydrostatic: the relaxation's records do not match its frames");
        for (int k = 0; k < r.relax_frames; ++k) r.relax_steps += steps[std::size_t(k)];
        r.relax_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }
    frame::Pipeline pipeline = simulation_only(scene, shaders);
    sim::Fluid& fluid = pipeline.simulation()->fluid();
    r.particles = fluid.count();
    if (!relaxed.empty()) fluid.upload_state(relaxed, std::vector<glm::vec4>(relaxed.size(), glm::vec4(0.0f)));
    StatsTally tally(scene, pipeline);
    tally.listen(fluid, r.steps);
    const int settle_frames = int(std::ceil(settle_s / scene.frame_dt));
    const int average_frames = std::max(int(std::ceil(average_s / scene.frame_dt)), 1);
    const int window_frames = int(std::ceil(0.5 / scene.frame_dt));
    r.average_seconds = average_frames * scene.frame_dt;
    if (progress) progress->expect(std::uint64_t(settle_frames + average_frames));
    const auto start = std::chrono::steady_clock::now();
    run(pipeline, settle_frames, progress);

    // The column starts uncompressed and rings acoustically (period 4 H / c); a snapshot lands at
    // some phase of that. So the pressure profile is averaged over the frames that follow, each
    // frame's state read back asynchronously (ParticleSnapshots): the frames run without a wait.
    const double rho0 = scene.sph.rest_density, g = glm::length(scene.gravity), dx = scene.spacing;
    r.reference_scale = rho0 * g * r.height;
    const int layers = int(std::ceil(r.height / dx)) + 2;
    // A profile's sums: pressure and particles per layer, over all particles and over the core.
    struct Sums {
        std::vector<double> sum, core_sum, speed2, vertical2;
        std::vector<long> n, core_n;
        explicit Sums(int layers)
            : sum(std::size_t(layers), 0.0), core_sum(std::size_t(layers), 0.0), speed2(std::size_t(layers), 0.0), vertical2(std::size_t(layers), 0.0), n(std::size_t(layers), 0),
              core_n(std::size_t(layers), 0) {}
    };
    Sums all(layers), window(layers);
    const double support = sim::kernel_support(scene.spacing);
    auto in_core = [&](const glm::vec4& p) {
        return p.x - scene.tank_min.x > support && scene.tank_max.x - p.x > support && p.z - scene.tank_min.z > support &&
               scene.tank_max.z - p.z > support;
    };
    // The errors of a profile's sums over `frames` frames, its layers into `out` when given.
    auto measure = [&](const Sums& s, int frames, HydrostaticResult& into, std::vector<HydrostaticResult::Layer>* out) {
        for (int k = 0; k < layers; ++k) {
            if (!s.n[std::size_t(k)]) continue;
            HydrostaticResult::Layer l;
            l.z = scene.tank_min.y + (k + 0.5) * dx;
            l.pressure = s.sum[std::size_t(k)] / double(s.n[std::size_t(k)]);
            l.reference = rho0 * g * std::max(r.height - (l.z - scene.tank_min.y), 0.0);
            l.particles = int(s.n[std::size_t(k)] / frames);
            l.rms_speed = std::sqrt(s.speed2[std::size_t(k)] / double(s.n[std::size_t(k)]));
            l.rms_vertical = std::sqrt(s.vertical2[std::size_t(k)] / double(s.n[std::size_t(k)]));
            if (out) out->push_back(l);
            // The hydrostatic law is compared in the interior: from one kernel support above the floor
            // (whose boundary term carries the bottom layer at about twice the pressure, docs/SPH.md
            // eq. (4)) to one below the free surface (where the summation density lacks neighbours
            // above and reads low). The layers outside are printed, not compared.
            const double from_floor = l.z - scene.tank_min.y;
            const double core = s.core_n[std::size_t(k)] ? s.core_sum[std::size_t(k)] / double(s.core_n[std::size_t(k)]) : l.reference;
            if (from_floor > support && from_floor < r.height - support) {
                into.max_error = std::max(into.max_error, std::abs(l.pressure - l.reference) / r.reference_scale);
                into.core_error = std::max(into.core_error, std::abs(core - l.reference) / r.reference_scale);
            }
            if (k == 0) {
                into.floor_error = std::abs(l.pressure - l.reference) / r.reference_scale;
                into.core_floor_error = std::abs(core - l.reference) / r.reference_scale;
            }
        }
        // Pairs of layers (k, k + 1) both in the interior, pooled: their pressure against the reference at
        // their particles' mean height, for k even and for k odd.
        auto inside = [&](int k) { const double z = (k + 0.5) * dx; return z > support && z < r.height - support; };
        for (int k = 0; k + 1 < layers; ++k) {
            const auto a = std::size_t(k), b = a + 1;
            if (!s.n[a] || !s.n[b] || !inside(k) || !inside(k + 1)) continue;
            const double n = double(s.n[a] + s.n[b]);
            const double z = (double(s.n[a]) * (k + 0.5) + double(s.n[b]) * (k + 1.5)) * dx / n;
            const double p = (s.sum[a] + s.sum[b]) / n;
            into.pair_error = std::max(into.pair_error, std::abs(p - rho0 * g * (r.height - z)) / r.reference_scale);
        }
        // The floor's pair, layers 0 and 1, the same way.
        if (layers > 1 && s.n[0] && s.n[1]) {
            const double n = double(s.n[0] + s.n[1]);
            const double z = (double(s.n[0]) * 0.5 + double(s.n[1]) * 1.5) * dx / n;
            into.floor_pair_error = std::abs((s.sum[0] + s.sum[1]) / n - rho0 * g * (r.height - z)) / r.reference_scale;
        }
    };
    Speeds end;   // of the last frame
    int seen = 0, in_window = 0;
    ParticleSnapshots state(fluid, ParticleSnapshots::kPositions | ParticleSnapshots::kDensities | ParticleSnapshots::kVelocities,
                            [&](const ParticleSnapshots::View& s) {
                                end = speeds(s.velocities);
                                r.mean_rms_speed += end.rms / average_frames;
                                for (std::size_t i = 0; i < s.positions.size(); ++i) {
                                    const glm::vec4& x = s.positions[i];
                                    const int k = int(std::floor((double(x.y) - scene.tank_min.y) / dx));
                                    if (k < 0 || k >= layers) continue;
                                    const bool core = in_core(x);
                                    for (Sums* t : {&all, &window}) {
                                        t->sum[std::size_t(k)] += s.densities[i].y, ++t->n[std::size_t(k)];
                                        t->speed2[std::size_t(k)] += double(glm::dot(glm::vec3(s.velocities[i]), glm::vec3(s.velocities[i])));
                                        t->vertical2[std::size_t(k)] += double(s.velocities[i].y) * double(s.velocities[i].y);
                                        if (core) t->core_sum[std::size_t(k)] += s.densities[i].y, ++t->core_n[std::size_t(k)];
                                    }
                                }
                                ++seen, ++in_window;
                                if (in_window == window_frames || seen == average_frames) {
                                    HydrostaticResult w;
                                    measure(window, in_window, w, nullptr);
                                    r.windows.push_back({(seen - in_window) * scene.frame_dt, w.max_error, w.floor_error});
                                    window = Sums(layers);
                                    in_window = 0;
                                }
                            });
    run_observed(pipeline, average_frames, progress, state);
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    r.stats = tally.end();
    r.max_speed = end.max;
    r.rms_speed = end.rms;
    measure(all, average_frames, r, &r.layers);
    return r;
}

scene::Scene standing_wave_scene() {
    return scene::parse(R"({
        "name": "standing-wave",
        "description": "Validation: the first sloshing mode of a 0.4 m tank, 0.1 m deep (docs/VALIDATION.md).",
        "model": "sph",
        "tank": { "min": [0.0, 0.0, 0.0], "max": [0.4, 0.3, 0.04] },
        "gravity": [0.0, -9.81, 0.0],
        "time": { "frame_dt": 0.016666667 },
        "particles": { "spacing": 0.01, "blocks": [ { "min": [0.0, 0.0, 0.0], "max": [0.4, 0.1, 0.04] } ] },
        "sph": { "rest_density": 1000, "viscosity": 1e-4, "boundary_rows": false,
                 "why": "Akinci's boundary term, not DFSPH's default rows: the slab is 4 particles deep between its front and back walls at 0.01 m, where the rows' period error is 4-9 % against Akinci's 0.03-4.5 %; at 0.005 m (8 deep) both are within 1 % (docs/DFSPH.md (D9))." }
    })", "the standing-wave case");
}

bool is_scene_case(const std::string& case_name) { return case_name.starts_with(kScenePrefix); }

std::vector<std::string> scene_cases() {
    std::vector<std::string> out;
    for (const scene::BundledScene& b : scene::bundled())
        if (scene::load(b.name).model == scene::Model::sph) out.push_back(kScenePrefix + b.name);
    return out;
}

scene::Scene case_scene(const std::string& name) {
    if (name == "standing-wave") return standing_wave_scene();
    if (name == "impact-pressure") return impact_pressure_scene();
    if (name == "obstacle-impact") return obstacle_impact_scene();
    if (name == "dam-break" || name == "hydrostatic") return scene::load(name);
    if (is_scene_case(name)) {
        const std::vector<std::string> sph = scene_cases();
        std::string list;
        for (const std::string& c : sph) list += (list.empty() ? "" : ", ") + c;
        const std::string scene_name = name.substr(std::string(kScenePrefix).size());
        if (std::find(sph.begin(), sph.end(), name) == sph.end()) {
            for (const scene::BundledScene& b : scene::bundled())
                if (b.name == scene_name)
                    throw InputError("case \"" + name + "\": the bundled scene " + scene_name +
                                     " uses the ballistic model, which has no pressure solver to sweep (scene cases: " + list + ")");
            throw InputError("case \"" + name + "\": no bundled SPH scene of that name (scene cases: " + list + ")");
        }
        return scene::load(scene_name);
    }
    throw InputError("unknown validation case \"" + name + "\" (cases: " + std::string(kCaseList) + ", scene:NAME of a bundled SPH scene)");
}

SceneRunResult scene_run(const scene::Scene& scene, const shader::FileSource& shaders, double seconds, frame::Progress* progress) {
    if (scene.model != scene::Model::sph) throw InputError("scene " + scene.name + ": a scene case must be an SPH scene");
    if (!(seconds > 0.0)) throw InputError("scene " + scene.name + ": a scene case runs for a positive time");
    SceneRunResult r;
    r.frames = std::max(1, int(std::lround(seconds / scene.frame_dt)));
    r.energy_conserving = !scene.turbulence.enabled();
    frame::Pipeline pipeline = simulation_only(scene, shaders);
    sim::Fluid& fluid = pipeline.simulation()->fluid();
    r.particles = fluid.count();
    StatsTally tally(scene, pipeline);
    tally.listen(fluid, r.steps);
    if (progress) progress->expect(std::uint64_t(r.frames));
    double sum = 0.0;
    int measured = 0;
    // Frame f's value (the pipeline's frames count from 0 here) is the state at t = (f + 1)·frame_dt.
    CompressionMeter meter(shaders, pipeline.timer(), fluid.count(), scene.sph.rest_density, [&](std::uint64_t frame, double c) {
        sum += c;
        ++measured;
        if (c > r.peak_mean_compression) r.peak_mean_compression = c, r.peak_time = double(frame + 1) * scene.frame_dt;
    });
    frame::FrameHooks hooks = progress ? progress->hooks() : frame::FrameHooks{};
    hooks.after_draw = [&](frame::Pipeline& p) { meter.measure(fluid.densities(), p.frames()); };   // after the frame's last step, in the frame
    hooks.after = [&meter, progress_after = hooks.after](frame::Pipeline& p) {
        meter.poll();
        if (progress_after) progress_after(p);
    };
    const auto start = std::chrono::steady_clock::now();
    run_with(pipeline, r.frames, hooks);
    meter.drain();
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    r.stats = tally.end();
    if (measured != r.frames)
        throw Error("scene " + scene.name + ": " + std::to_string(measured) + " compressions came back for " + std::to_string(r.frames) + " frames");
    r.average_mean_compression = sum / double(r.frames);
    return r;
}

StandingWaveResult standing_wave(const scene::Scene& given, const shader::FileSource& shaders, frame::Progress* progress) {
    if (given.model != scene::Model::sph || given.blocks.size() != 1) throw InputError("standing-wave: the scene must be SPH with one block");
    StandingWaveResult r;
    const scene::Block water = given.blocks.front();
    const double dx = given.spacing;
    // The depth and length SPH sees are those of the lattice that fills the block (whole layers and
    // columns of dx), not the block's nominal box: at dx = 0.0133 m a 0.1 m block holds 7 layers,
    // 0.093 m, which moves T by 2.5 % (docs/VALIDATION.md "Standing wave").
    const int columns = int(std::floor((water.max.x - water.min.x) / dx + 1e-4)),
              layers = int(std::floor((water.max.y - water.min.y) / dx + 1e-4));
    if (columns < 2 || layers < 2) throw InputError("standing-wave: spacing " + std::to_string(dx) + " leaves fewer than two columns or layers");
    r.length = given.tank_max.x - given.tank_min.x;
    r.depth = double(layers) * dx + (water.min.y - given.tank_min.y);
    r.amplitude = 0.1 * r.depth;
    r.spacing = dx;
    r.wavenumber = std::numbers::pi / r.length;
    const double g = glm::length(given.gravity), k = r.wavenumber;
    r.period_theory = 2.0 * std::numbers::pi / std::sqrt(g * k * std::tanh(k * r.depth));
    r.decay_theory = 2.0 * given.sph.viscosity * k * k;
    // The surface raised to η(x) = H + A cos(k x) at rest density: column c of the lattice (centre
    // x_c) holds n_c = round(η(x_c)/dx) layers, each particle's height above the floor then stretched
    // by η(x_c)/(n_c dx). The stretch is within 1 ± 1/(2 n_c): half a layer over the column at any
    // resolution. (Stretching every column of the block's n layers to η instead compresses the
    // liquid by up to A/H = 10 % at every resolution, and the incompressible solvers' first steps
    // turn that into speeds of (A/H)·H/dt, which blew up DFSPH at dx <= 0.005 m.)
    scene::Scene scene = given;
    scene.blocks.clear();
    std::vector<double> stretch(std::size_t(columns), 1.0);
    const double floor_y = given.tank_min.y;
    for (int c = 0; c < columns; ++c) {
        const double xc = water.min.x + (c + 0.5) * dx;
        const double eta = r.depth + r.amplitude * std::cos(k * (xc - given.tank_min.x)) - (water.min.y - floor_y);
        const int n = std::max(1, int(std::lround(eta / dx)));
        stretch[std::size_t(c)] = eta / (double(n) * dx);
        scene::Block b = water;
        b.min.x = float(water.min.x + c * dx);
        b.max.x = float(water.min.x + (c + 1) * dx);
        b.max.y = float(water.min.y + n * dx);
        scene.blocks.push_back(b);
    }
    frame::Pipeline pipeline = simulation_only(scene, shaders);
    sim::Fluid& fluid = pipeline.simulation()->fluid();
    r.particles = fluid.count();
    std::vector<glm::vec4> x = fluid.positions().read<glm::vec4>(fluid.count());
    for (glm::vec4& p : x) {
        const int c = std::clamp(int(std::floor((double(p.x) - water.min.x) / dx)), 0, columns - 1);
        p.y = float(water.min.y + (double(p.y) - water.min.y) * stretch[std::size_t(c)]);
    }
    fluid.upload_state(x, std::vector<glm::vec4>(x.size(), glm::vec4(0.0f)));
    StatsTally tally(scene, pipeline);
    tally.listen(fluid, r.steps);
    const int frames = int(std::ceil(3.0 * r.period_theory / scene.frame_dt));
    r.moment.reserve(std::size_t(frames) + 1);
    // m(t) of each frame's positions, read back asynchronously: the frames run without a wait.
    ParticleSnapshots positions(fluid, ParticleSnapshots::kPositions, [&](const ParticleSnapshots::View& s) {
        double m = 0.0;
        for (const glm::vec4& q : s.positions) m += (double(q.y) - scene.tank_min.y) * std::cos(k * (double(q.x) - scene.tank_min.x));
        r.moment.emplace_back(double(s.tag) * scene.frame_dt, m / double(std::max<std::size_t>(s.positions.size(), 1)));
    });
    if (progress) progress->expect(std::uint64_t(frames));
    const auto start = std::chrono::steady_clock::now();
    positions.capture(0);   // the start, t = 0; frame f's state is tagged f + 1
    run_observed(pipeline, frames, progress, positions);
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    r.stats = tally.end();

    measure_mode(r);
    return r;
}

void measure_mode(StandingWaveResult& r) {
    // The mean crossings (linear between frames) over the run, after the first quarter period:
    // consecutive ones are half a period apart.
    double mean = 0.0;
    for (const auto& [t, m] : r.moment) mean += m;
    mean /= double(r.moment.size());
    std::vector<double> crossings;
    for (std::size_t i = 1; i < r.moment.size(); ++i) {
        const double a = r.moment[i - 1].second - mean, b = r.moment[i].second - mean;
        if ((a < 0.0) != (b < 0.0) && r.moment[i].first > 0.25 * r.period_theory) {
            const double w = a / (a - b);
            crossings.push_back(r.moment[i - 1].first + w * (r.moment[i].first - r.moment[i - 1].first));
        }
    }
    if (crossings.size() < 2) throw NoMeasurement("standing-wave: the surface did not oscillate (fewer than two mean crossings)");
    r.half_periods = int(crossings.size()) - 1;
    r.period = 2.0 * (crossings.back() - crossings.front()) / double(r.half_periods);
    r.period_error = std::abs(r.period - r.period_theory) / r.period_theory;
    // Decay: the largest |m - mean| of the first and of the last half period between crossings.
    auto swing = [&](double from, double to) {
        double s = 0.0;
        for (const auto& [t, m] : r.moment)
            if (t >= from && t <= to) s = std::max(s, std::abs(m - mean));
        return s;
    };
    const double first = swing(crossings[0], crossings[1]), last = swing(crossings[crossings.size() - 2], crossings.back());
    const double span = 0.5 * (crossings.back() + crossings[crossings.size() - 2]) - 0.5 * (crossings[0] + crossings[1]);
    r.decay_rate = first > 0.0 && last > 0.0 && span > 0.0 ? std::log(first / last) / span : 0.0;
}

scene::Scene impact_pressure_scene() {
    return scene::parse(scene::bundled_file("validation/impact-pressure.json"), "the impact-pressure case (media/validation/impact-pressure.json)");
}

scene::Scene obstacle_impact_scene() {
    return scene::parse(scene::bundled_file("validation/obstacle-impact.json"), "the obstacle-impact case (media/validation/obstacle-impact.json)");
}

double probe_pressure(const Probe& probe, std::span<const glm::vec4> positions, std::span<const glm::vec4> densities) {
    const double r2max = probe.radius * probe.radius;
    double sum = 0.0, weight = 0.0;
    for (std::size_t i = 0; i < positions.size(); ++i) {
        const glm::vec4& x = positions[i];
        if (x.w < -0.5 || double(x.z) < probe.z_lo || double(x.z) > probe.z_hi) continue;   // parked (sim/fluid.h), or off the strip
        if (probe.side != 0.0 && probe.side * (double(x.x) - probe.face) <= 0.0) continue;   // behind the face (side 0: no face)
        const double dx = double(x.x) - probe.x, dy = double(x.y) - probe.y, r2 = dx * dx + dy * dy;
        if (r2 >= r2max) continue;
        const double q = 1.0 - r2 / r2max, w = q * q * q;
        sum += w * double(densities[i].y);
        weight += w;
    }
    return weight > 0.0 ? sum / weight : 0.0;
}

namespace {
// The first time series `s` (sorted by time) reaches `level`, linear between samples.
std::optional<double> first_reaching(const std::vector<std::pair<double, double>>& s, double level) {
    for (std::size_t i = 0; i < s.size(); ++i) {
        if (s[i].second < level) continue;
        if (i == 0) return s[i].first;
        const auto& [t0, p0] = s[i - 1];
        const auto& [t1, p1] = s[i];
        return t0 + (level - p0) / (p1 - p0) * (t1 - t0);
    }
    return std::nullopt;
}

// A case's sensors on the face x = `face` of a wall or an obstacle, the fluid arriving from the side
// `side` (−1: from smaller x, +1: from larger), over the strip [z_lo, z_hi] across it.
struct SensorSpec {
    const char* name;
    const char* file;    // under media/validation/
    double height;       // above the floor, in the experiment (m)
};
struct SensorFace {
    std::string label, source;
    double experiment_height = 0.0;   // the experiment's H (m): the sensors' heights scale with the column's
    double face = 0.0;                // x of the face
    double side = 0.0;                // −1: the fluid arrives from smaller x, +1: from larger
    double z_lo = 0.0, z_hi = 0.0;    // the strip across the face
    double window_from = 0.0, window_to = 0.0;
    std::vector<SensorSpec> sensors;
};

ImpactPressureResult run_sensors(const scene::Scene& scene, const shader::FileSource& shaders, frame::Progress* progress, double until,
                                 const SensorFace& f) {
    const scene::Block& column = scene.blocks.front();
    ImpactPressureResult r;
    r.source = f.source;
    r.spacing = scene.spacing;
    // H is the depth of the lattice that fills the column, whole layers of dx (as the tank at rest's):
    // the fluid's own column, which sets the flow's time and pressure scales; the sensors stand at the
    // experiment's heights scaled with the column's block.
    const double nominal = column.max.y - column.min.y;
    const int layers = int(std::floor(nominal / r.spacing + 1e-4));   // at least two (check_case_scene)
    r.height = layers * r.spacing + (column.min.y - scene.tank_min.y);
    r.face = f.face;
    r.window[0] = f.window_from, r.window[1] = f.window_to;
    const double g = glm::length(scene.gravity), rho0 = scene.sph.rest_density;
    const double time_scale = std::sqrt(g / r.height), pressure_scale = rho0 * g * r.height;   // T = t sqrt(g/H), p/(rho0 g H)
    double last = 0.0;
    for (const SensorSpec& spec : f.sensors) {
        ImpactPressureResult::Sensor s;
        s.name = spec.name;
        s.z = spec.height * nominal / f.experiment_height;
        s.measured = read_series(scene::bundled_file(std::string("validation/") + spec.file));
        if (s.measured.empty()) throw Error(f.label + ": no data for sensor " + spec.name);
        last = std::max(last, s.measured.back().first);
        r.sensors.push_back(std::move(s));
    }
    if (until <= 0.0) until = last;
    if (until < f.window_to)
        throw InputError(f.label + ": a run to T = " + std::to_string(until) + " leaves out the compared window, which ends at T = " +
                         std::to_string(f.window_to));
    // The probe: half a spacing off the face on the fluid's side (where the fluid's first layer lies
    // against it), a kernel support across, over the strip; nothing behind the face.
    Probe probe;
    probe.x = f.face + f.side * 0.5 * r.spacing;
    probe.face = f.face;
    probe.side = f.side;
    probe.z_lo = f.z_lo;
    probe.z_hi = f.z_hi;
    probe.radius = sim::kernel_support(float(r.spacing));
    const int frames = int(std::ceil(until / time_scale / scene.frame_dt));

    frame::Pipeline pipeline = simulation_only(scene, shaders);
    sim::Fluid& fluid = pipeline.simulation()->fluid();
    r.particles = fluid.count();
    // Each frame's sample stands at the time its pressure is of (the solver's Density.y: sim/solver.h).
    r.sample_offset = pipeline.simulation()->solver().pressure_sample_offset();
    StatsTally tally(scene, pipeline);
    tally.listen(fluid, r.steps);
    for (auto& s : r.sensors) s.simulated.reserve(std::size_t(frames) + 1);
    ParticleSnapshots state(fluid, ParticleSnapshots::kPositions | ParticleSnapshots::kDensities, [&](const ParticleSnapshots::View& v) {
        const double T = (double(v.tag) - r.sample_offset) * scene.frame_dt * time_scale;
        for (auto& s : r.sensors) {
            probe.y = scene.tank_min.y + s.z;
            s.simulated.emplace_back(T, probe_pressure(probe, v.positions, v.densities) / pressure_scale);
        }
    });
    if (progress) progress->expect(std::uint64_t(frames));
    const auto start = std::chrono::steady_clock::now();
    run_observed(pipeline, frames, progress, state);
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    r.stats = tally.end();
    for (auto& s : r.sensors) {
        try {
            compare_sensor(s, f.window_from, f.window_to);
        } catch (const NoMeasurement& e) {
            throw NoMeasurement(f.label + ": " + e.what());
        }
    }
    return r;
}
}  // namespace

void compare_sensor(ImpactPressureResult::Sensor& s, double window_from, double window_to) {
    s.onset_measured = first_reaching(s.measured, kImpactOnset);
    s.onset_simulated = first_reaching(s.simulated, kImpactOnset);
    s.peak_measured = s.peak_simulated = 0.0;
    for (const auto& [t, p] : s.measured) s.peak_measured = std::max(s.peak_measured, p);
    for (const auto& [t, p] : s.simulated) s.peak_simulated = std::max(s.peak_simulated, p);
    // The experiment's samples in the window that the simulation covers, each weighted by half the time
    // to its neighbours there (the trapezoid rule): a digitised series samples some stretches more
    // densely than others, and the means are over time, not over samples.
    std::vector<std::pair<double, double>> at;   // (T, p) measured, with the simulation's p beside
    std::vector<double> sim;
    for (const auto& [t, p] : s.measured) {
        if (t < window_from || t > window_to) continue;
        const auto q = interpolate(s.simulated, t);
        if (!q) continue;
        at.emplace_back(t, p);
        sim.push_back(*q);
    }
    s.compared = int(at.size());
    if (s.compared == 0)
        throw NoMeasurement("sensor " + s.name + "'s simulated readings cover none of the experiment's times in T = [" +
                            std::to_string(window_from) + ", " + std::to_string(window_to) + "]");
    double weight = 0.0, sum_m = 0.0, sum_s = 0.0, sum2 = 0.0;
    for (std::size_t k = 0; k < at.size(); ++k) {
        const double w = at.size() == 1 ? 1.0 : 0.5 * ((k + 1 < at.size() ? at[k + 1].first : at[k].first) - (k > 0 ? at[k - 1].first : at[k].first));
        weight += w, sum_m += w * at[k].second, sum_s += w * sim[k], sum2 += w * (sim[k] - at[k].second) * (sim[k] - at[k].second);
    }
    if (weight <= 0.0) weight = 1.0, sum_m = at[0].second, sum_s = sim[0], sum2 = (sim[0] - at[0].second) * (sim[0] - at[0].second);
    s.mean_measured = sum_m / weight;
    s.mean_simulated = sum_s / weight;
    s.rms_error = std::sqrt(sum2 / weight);
}

void check_case_scene(const std::string& case_name, const scene::Scene& scene) {
    if (case_name != "impact-pressure" && case_name != "obstacle-impact") return;
    if (case_name == "impact-pressure") {
        if (scene.model != scene::Model::sph || scene.blocks.size() != 1 || !scene.obstacles.empty())
            throw InputError("impact-pressure: the scene must be SPH with one block and no obstacle");
        if (scene.blocks.front().min.x > scene.tank_min.x + 1e-6f)
            throw InputError("impact-pressure: the column must stand against the tank's wall at x = " + std::to_string(scene.tank_min.x) +
                             " (the wall it strikes is the other end, x = " + std::to_string(scene.tank_max.x) + ")");
    } else {
        if (scene.model != scene::Model::sph || scene.blocks.size() != 1 || scene.obstacles.empty() ||
            scene.obstacles.front().kind != scene::Obstacle::Kind::box)
            throw InputError("obstacle-impact: the scene must be SPH with one block and a box obstacle");
        if (scene.blocks.front().min.x <= scene.obstacles.front().max.x)
            throw InputError("obstacle-impact: the column (from x = " + std::to_string(scene.blocks.front().min.x) +
                             ") must lie beyond the box's face at x = " + std::to_string(scene.obstacles.front().max.x));
    }
    const scene::Block& column = scene.blocks.front();
    if (int(std::floor((column.max.y - column.min.y) / scene.spacing + 1e-4)) < 2)
        throw InputError(case_name + ": spacing " + std::to_string(scene.spacing) + " leaves the column fewer than two layers");
}

ImpactPressureResult impact_pressure(const scene::Scene& scene, const shader::FileSource& shaders, frame::Progress* progress, double until) {
    check_case_scene("impact-pressure", scene);
    // The wall struck is the tank's far end; the strip the middle half of the tank's width (the side
    // walls' boundary layers aside).
    const double width = scene.tank_max.z - scene.tank_min.z;
    const SensorFace f{.label = "impact-pressure",
                       .source = "Lobovsky et al. 2014, J. Fluids Struct. 48, H = 300 mm, sensors 1, 3 and 4",
                       .experiment_height = 0.3,
                       .face = scene.tank_max.x,
                       .side = -1.0,
                       .z_lo = scene.tank_min.z + 0.25 * width,
                       .z_hi = scene.tank_max.z - 0.25 * width,
                       .window_from = 3.0,
                       .window_to = 5.5,
                       .sensors = {{"P1", "lobovsky_exp_data_p1.csv", 0.003},
                                   {"P3", "lobovsky_exp_data_p3.csv", 0.030},
                                   {"P4", "lobovsky_exp_data_p4.csv", 0.080}}};
    return run_sensors(scene, shaders, progress, until, f);
}

bool is_impact_case(const std::string& case_name) { return case_name == "impact-pressure" || case_name == "obstacle-impact"; }

ImpactPressureResult impact_case(const std::string& case_name, const scene::Scene& scene, const shader::FileSource& shaders,
                                 frame::Progress* progress) {
    if (case_name == "impact-pressure") return impact_pressure(scene, shaders, progress);
    if (case_name == "obstacle-impact") return obstacle_impact(scene, shaders, progress);
    throw InputError("unknown impact case '" + case_name + "' (impact-pressure, obstacle-impact)");
}

ImpactPressureResult obstacle_impact(const scene::Scene& scene, const shader::FileSource& shaders, frame::Progress* progress, double until) {
    check_case_scene("obstacle-impact", scene);
    // The box's face towards the column, which lies at larger x; the strip the middle half of its width.
    const scene::Obstacle& box = scene.obstacles.front();
    const double width = box.max.z - box.min.z;
    const SensorFace f{.label = "obstacle-impact",
                       .source = "Kleefsman et al. 2005, J. Comput. Phys. 206 (SPHERIC test 2), H = 0.55 m, sensors P1 and P3",
                       .experiment_height = 0.55,
                       .face = box.max.x,
                       .side = 1.0,
                       .z_lo = box.min.z + 0.25 * width,
                       .z_hi = box.max.z - 0.25 * width,
                       .window_from = 2.5,
                       .window_to = 7.0,
                       .sensors = {{"P1", "kleefsman_exp_data_p1.csv", 0.021}, {"P3", "kleefsman_exp_data_p3.csv", 0.101}}};
    return run_sensors(scene, shaders, progress, until, f);
}

}  // namespace ranryu::validation
