#pragma once
// Per-pass timing summaries: the table `ranryu profile` prints and the JSON/CSV it writes.
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "profile/gpu_timer.h"

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
    int substeps = 0;       // per frame; 0: adaptive (SPH: the substeps are chosen on the GPU)
    double frame_dt = 0.0;  // simulated seconds per frame
};

struct PassRow {
    std::string name;
    double calls_per_frame = 0.0;
    double min_ms = 0.0, median_ms = 0.0, max_ms = 0.0;   // per frame, the pass's calls summed
    double ms_per_call = 0.0;                             // all its time over all its calls
    double share = 0.0;                                   // of the summed GPU frame spans
};

struct Report {
    RunInfo info;
    std::vector<PassRow> passes;   // in order of first use
    PassRow frame;                 // the whole GPU span of a frame
};

Report summarize(const GpuTimer& timer, RunInfo info);
std::string table(const Report& r);
nlohmann::json to_json(const Report& r);
std::string to_csv(const Report& r);

std::string utc_now_iso8601();

// Writes a whole text file atomically ("<path>.tmp", then rename). `what` names the input in the
// error (e.g. "--json out.json"); failure raises ranryu::InputError.
void write_text_file(const std::filesystem::path& path, const std::string& text, const std::string& what);

}  // namespace ranryu::profile
