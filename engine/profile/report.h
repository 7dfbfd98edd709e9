#pragma once
// Per-pass timing summaries: the table `ranryu profile` prints and the JSON/CSV it writes.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "profile/gpu_timer.h"
#include "shared/bindings.h"

namespace ranryu::profile {

struct RunInfo {
    std::string renderer;   // GL_RENDERER
    std::string driver;     // GL_VERSION (carries the driver version)
    std::string platform;   // EGL device / EGL surfaceless / GLFW
    std::string date;       // UTC, ISO 8601
    std::string scene;
    std::size_t particles = 0;
    int width = 0, height = 0;
    int frames = 0;         // frames timed (after warm-up)
    int warmup = 0;
    int substeps = 0;       // per frame; 0: adaptive (SPH but PBF: the substeps are chosen on the GPU)
    double frame_dt = 0.0;  // simulated seconds per frame
};

struct PassRow {
    std::string name;
    std::string within;   // the pass it runs within (GpuTimer::pass(name, within)), or "": its time is in that one's too
    double calls_per_frame = 0.0;
    double min_ms = 0.0, median_ms = 0.0, max_ms = 0.0;   // per frame, the pass's calls summed
    double ms_per_call = 0.0;                             // all its time over all its calls
    double share = 0.0;                                   // of the summed GPU frame spans
};

// What an SPH simulation did over the timed frames, from the StepState records that came back.
struct SimulationSummary {
    std::string solver;                        // dfsph | wcsph | pbf
    std::uint64_t frames = 0, steps = 0;
    double start_time = 0.0;                   // simulated time when the timed frames began (s)
    double simulated_seconds = 0.0;            // over those frames
    double wall_seconds = 0.0;                 // the timed frames on the CPU's clock
    std::uint32_t most_substeps = 0;           // in one frame
    // The pressure solve's iterations (DFSPH; 0 for WCSPH): per step, and the most in one step.
    double iterations = 0.0, divergence_iterations = 0.0;
    std::uint32_t most_iterations = 0, most_divergence_iterations = 0;
    std::uint64_t unconverged = 0, unconverged_divergence = 0;   // steps that stopped at the issued cap
    // The iterations the CPU issued (its caps, docs/DFSPH.md "The iteration cap"), per step: those past
    // what ran dispatched no work but cost a dispatch and a barrier each.
    double issued = 0.0, issued_divergence = 0.0;
    double density_error = 0.0, max_density_error = 0.0;         // the solve's last mean error (units of rho0): per step, most
    double peak_density_error = 0.0;   // the largest particle error a density solve stopped with (units of rho0; (D6))
    double divergence_error = 0.0;
    // The step the density solve's iterations allowed (docs/DFSPH.md (D8)) at the end of a frame, the
    // least over the frames (s; sph.dt_max where no solve lowered it).
    double least_iteration_dt = 0.0;

    void add(const gpu::StepState& record);    // one frame's record, in frame order
    double substeps_per_frame() const { return frames ? double(steps) / double(frames) : 0.0; }
};

// A pass that runs within another and was not timed apart (GpuTimer::set_detail(false)): its calls
// are counted, its time is its parent's.
struct UntimedPass {
    std::string name, within;
    double calls_per_frame = 0.0;
};

struct Report {
    RunInfo info;
    std::vector<PassRow> passes;   // in order of first use; a pass within another follows it
    std::vector<UntimedPass> untimed_within;   // in the order they were named
    bool detail = false;           // some pass within another was timed apart: a row has `within`
    PassRow frame;                 // the whole GPU span of a frame
    std::uint64_t frames_sampled = 0;   // frames whose timings came back (the rows' samples)
    std::uint64_t frames_skipped = 0;   // frames not timed: the timer's ring was full (GpuTimer)
    std::optional<SimulationSummary> simulation;
    // Frames a second and simulated seconds a second, by the GPU's frame spans and by the wall clock.
    double fps_gpu() const;
    double fps_wall() const;
    double real_time_factor_gpu() const;
    double real_time_factor_wall() const;
};

Report summarize(const GpuTimer& timer, RunInfo info, std::optional<SimulationSummary> simulation = std::nullopt);
std::string table(const Report& r);
nlohmann::json to_json(const Report& r);
std::string to_csv(const Report& r);

// One StepState record as a CSV row (and the header naming its columns): the frame, simulated time,
// steps, the smallest stable dt, largest speed and density, solver iterations and errors, guard counts,
// and where the frame's fastest and densest particles were (fastest_x..z, densest_x..z, m).
std::string record_csv_header();
std::string record_csv_row(const gpu::StepState& r);

std::string utc_now_iso8601();

// Writes a whole text file atomically ("<path>.tmp", then rename). `what` names the input in the
// error (e.g. "--json out.json"); failure raises ranryu::InputError.
void write_text_file(const std::filesystem::path& path, const std::string& text, const std::string& what);

// Checks, before any work, that write_text_file() (or any writer that writes "<path>.tmp" and renames it)
// will be able to write `path`: not a folder, its folder there, "<path>.tmp" creatable (made and removed;
// an existing `path` is not touched). Raises ranryu::InputError naming `what` and the reason.
void check_writable(const std::filesystem::path& path, const std::string& what);

}  // namespace ranryu::profile
