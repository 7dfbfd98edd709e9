#include "profile/report.h"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <bit>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <numeric>
#include <sstream>

#include "core/error.h"

namespace ranryu::profile {
namespace {

PassRow row(const std::string& name, std::vector<double> ms, double calls, double total_frame_ms) {
    PassRow r;
    r.name = name;
    r.calls_per_frame = calls;
    if (ms.empty()) return r;
    const double sum = std::accumulate(ms.begin(), ms.end(), 0.0);
    std::sort(ms.begin(), ms.end());
    r.min_ms = ms.front();
    r.max_ms = ms.back();
    const std::size_t n = ms.size();
    r.median_ms = n % 2 ? ms[n / 2] : 0.5 * (ms[n / 2 - 1] + ms[n / 2]);
    r.share = total_frame_ms > 0.0 ? sum / total_frame_ms : 0.0;
    return r;
}

std::string csv_field(const std::string& s) {
    if (s.find_first_of(",\"\n") == std::string::npos) return s;
    std::string out = "\"";
    for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
    return out + "\"";
}

}  // namespace

void SimulationSummary::add(const gpu::StepState& r) {
    ++frames;
    simulated_seconds = double(r.time) - start_time;
    steps += r.frame_substeps;
    most_substeps = std::max(most_substeps, r.frame_substeps);
    iterations += r.iterations.x;
    divergence_iterations += r.iterations.y;
    most_iterations = std::max(most_iterations, r.iterations.z);
    most_divergence_iterations = std::max(most_divergence_iterations, r.iterations.w);
    unconverged += r.unconverged.x;
    unconverged_divergence += r.unconverged.y;
    issued += r.issued;
    issued_divergence += r.issued_divergence;
    density_error += r.error.x;
    divergence_error += r.error.y;
    max_density_error = std::max(max_density_error, double(r.error.z));
    peak_density_error = std::max(peak_density_error, double(std::bit_cast<float>(r.peak_error)));
    least_iteration_dt = frames == 1 ? double(r.iteration_dt) : std::min(least_iteration_dt, double(r.iteration_dt));
}

namespace {
// The summary's sums as per-step means.
SimulationSummary per_step(SimulationSummary s) {
    const double n = double(std::max<std::uint64_t>(s.steps, 1));
    s.iterations /= n;
    s.divergence_iterations /= n;
    s.issued /= n;
    s.issued_divergence /= n;
    s.density_error /= n;
    s.divergence_error /= n;
    return s;
}
}  // namespace

double Report::fps_gpu() const { return frame.ms_per_call > 0.0 ? 1000.0 / frame.ms_per_call : 0.0; }
double Report::fps_wall() const {
    return simulation && simulation->wall_seconds > 0.0 ? double(info.frames) / simulation->wall_seconds : 0.0;
}
double Report::real_time_factor_gpu() const {
    if (simulation && simulation->frames) return simulation->simulated_seconds / double(simulation->frames) * fps_gpu();
    return info.frame_dt * fps_gpu();
}
double Report::real_time_factor_wall() const {
    return simulation && simulation->wall_seconds > 0.0 ? simulation->simulated_seconds / simulation->wall_seconds : 0.0;
}

Report summarize(const GpuTimer& timer, RunInfo info, std::optional<SimulationSummary> simulation) {
    Report r;
    r.info = std::move(info);
    if (simulation) r.simulation = per_step(*simulation);
    const auto& frames = timer.frame_ms();
    const double total = std::accumulate(frames.begin(), frames.end(), 0.0);
    const double nframes = double(std::max<std::size_t>(frames.size(), 1));
    for (const std::uint16_t index : timer.first_use_order()) {
        const PassSamples& p = timer.passes()[index];
        if (p.ms.empty()) continue;
        const double all_calls = std::accumulate(p.calls.begin(), p.calls.end(), 0.0);
        PassRow pr = row(p.name, p.ms, all_calls / nframes, total);
        pr.ms_per_call = std::accumulate(p.ms.begin(), p.ms.end(), 0.0) / std::max(all_calls, 1.0);
        if (p.within >= 0) pr.within = timer.passes()[std::size_t(p.within)].name;
        r.passes.push_back(pr);
    }
    // A pass within another comes right after it (and after the others within it that ran first): rows
    // ordered by their parent's first use, then their own.
    {
        std::vector<std::pair<std::size_t, std::size_t>> key(r.passes.size());
        for (std::size_t k = 0; k < r.passes.size(); ++k) {
            std::size_t parent = k;
            for (std::size_t q = 0; q < r.passes.size(); ++q)
                if (!r.passes[k].within.empty() && r.passes[q].name == r.passes[k].within) parent = q;
            key[k] = {parent, k};
        }
        std::vector<std::size_t> order(r.passes.size());
        std::iota(order.begin(), order.end(), std::size_t(0));
        std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return key[a] < key[b]; });
        std::vector<PassRow> sorted;
        sorted.reserve(order.size());
        for (const std::size_t k : order) sorted.push_back(std::move(r.passes[k]));
        r.passes = std::move(sorted);
    }
    r.detail = std::any_of(r.passes.begin(), r.passes.end(), [](const PassRow& p) { return !p.within.empty(); });
    const std::vector<std::uint64_t> untimed = timer.untimed_calls();
    for (std::size_t k = 0; k < timer.passes().size(); ++k) {
        const PassSamples& p = timer.passes()[k];
        if (p.within < 0 || untimed[k] == 0) continue;
        r.untimed_within.push_back(UntimedPass{p.name, timer.passes()[std::size_t(p.within)].name, double(untimed[k]) / nframes});
    }
    r.frame = row("frame (GPU span)", frames, 1.0, total);
    r.frame.ms_per_call = total / nframes;
    r.frames_sampled = frames.size();
    r.frames_skipped = timer.skipped_frames();
    return r;
}

std::string table(const Report& r) {
    std::ostringstream out;
    char line[256];
    out << r.info.renderer << " | " << r.info.driver << " | " << r.info.date << "\n";
    out << "scene " << r.info.scene << ": " << r.info.particles << " particles, " << r.info.width << "x"
        << r.info.height << ", " << r.info.frames << " frames timed after " << r.info.warmup << " warm-up, "
        << (r.info.substeps > 0 ? std::to_string(r.info.substeps) + " substeps/frame"
                                : std::string("adaptive substeps (see the simulation line)"))
        << "\n";
    std::snprintf(line, sizeof line, "%-29s %9s %10s %10s %10s %10s %7s\n", "pass", "calls/fr", "min ms", "median ms",
                  "max ms", "ms/call", "share");
    out << line;
    auto print = [&](const PassRow& p) {
        // A pass within another is indented under it: its time is in its parent's row too.
        const std::string name = (p.within.empty() ? "" : "  ") + p.name;
        std::snprintf(line, sizeof line, "%-29s %9.2f %10.4f %10.4f %10.4f %10.4f %6.1f%%\n", name.c_str(),
                      p.calls_per_frame, p.min_ms, p.median_ms, p.max_ms, p.ms_per_call, 100.0 * p.share);
        out << line;
    };
    for (const PassRow& p : r.passes) print(p);
    print(r.frame);
    if (r.frames_skipped)   // the GPU ran a whole timer ring behind: those frames went untimed, not waited for
        out << r.frames_skipped << " frames not timed (the timer's ring was full), " << r.frames_sampled << " timed\n";
    out << "\n";   // the table ends; what the run did follows
    if (r.detail)
        out << "--detail: the indented passes ran within the pass above them, each dispatch timed apart; their shares are in\n"
               "  their parent's, and the timestamps around each add GPU time (docs/PERFORMANCE.md \"Passes within passes, timed apart\")\n";
    if (!r.untimed_within.empty()) {
        out << "timed within their passes, not apart (profile --detail times each):";
        const char* sep = " ";
        for (const UntimedPass& u : r.untimed_within) {
            std::snprintf(line, sizeof line, "%s%s %.1f calls/fr in %s", sep, u.name.c_str(), u.calls_per_frame, u.within.c_str());
            out << line;
            sep = ", ";
        }
        out << "\n";
    }
    if (const auto& s = r.simulation) {
        std::snprintf(line, sizeof line, "simulation (%s): %.1f substeps/frame (most %u), %.4f simulated s/frame\n",
                      s->solver.c_str(), s->substeps_per_frame(), s->most_substeps,
                      s->frames ? s->simulated_seconds / double(s->frames) : 0.0);
        out << line;
        if (s->solver == "dfsph") {
            std::snprintf(line, sizeof line,
                          "  density solve: %.2f iterations/step (most %u, %llu steps stopped at the cap; %.1f issued), "
                          "mean error %.3f %% (most %.3f %%), one particle's at most %.3f %%\n",
                          s->iterations, s->most_iterations, static_cast<unsigned long long>(s->unconverged), s->issued,
                          100.0 * s->density_error, 100.0 * s->max_density_error, 100.0 * s->peak_density_error);
            out << line;
            std::snprintf(line, sizeof line,
                          "  divergence solve: %.2f iterations/step (most %u, %llu at the cap; %.1f issued), mean error %.3f %%\n",
                          s->divergence_iterations, s->most_divergence_iterations,
                          static_cast<unsigned long long>(s->unconverged_divergence), s->issued_divergence, 100.0 * s->divergence_error);
            out << line;
            std::snprintf(line, sizeof line, "  the step the iterations allow (D8): least %.3f ms at a frame's end\n",
                          1000.0 * s->least_iteration_dt);
            out << line;
        } else if (s->solver == "pbf") {
            std::snprintf(line, sizeof line, "  position solve: %.2f iterations/step (fixed, sph.pbf.iterations)\n", s->iterations);
            out << line;
        }
    }
    std::snprintf(line, sizeof line, "%.1f fps and real-time factor %.3f by the GPU's frame spans", r.fps_gpu(),
                  r.real_time_factor_gpu());
    out << line;
    if (r.fps_wall() > 0.0) {
        std::snprintf(line, sizeof line, "; %.1f fps and %.3f by the wall clock", r.fps_wall(), r.real_time_factor_wall());
        out << line;
    }
    out << "\n";
    return out.str();
}

nlohmann::json to_json(const Report& r) {
    auto pass = [](const PassRow& p) {
        nlohmann::json j{{"name", p.name},       {"calls_per_frame", p.calls_per_frame},
                         {"min_ms", p.min_ms},   {"median_ms", p.median_ms},
                         {"max_ms", p.max_ms},   {"ms_per_call", p.ms_per_call},
                         {"share", p.share}};
        if (!p.within.empty()) j["within"] = p.within;
        return j;
    };
    nlohmann::json passes = nlohmann::json::array();
    for (const PassRow& p : r.passes) passes.push_back(pass(p));
    nlohmann::json untimed = nlohmann::json::array();
    for (const UntimedPass& u : r.untimed_within)
        untimed.push_back({{"name", u.name}, {"within", u.within}, {"calls_per_frame", u.calls_per_frame}});
    nlohmann::json j = {{"device", r.info.renderer},
            {"driver", r.info.driver},
            {"platform", r.info.platform},
            {"date", r.info.date},
            {"scene", r.info.scene},
            {"particles", r.info.particles},
            {"width", r.info.width},
            {"height", r.info.height},
            {"frames", r.info.frames},
            {"warmup_frames", r.info.warmup},
            {"frames_sampled", r.frames_sampled},
            {"frames_skipped", r.frames_skipped},
            {"substeps_per_frame", r.info.substeps},
            {"simulated_seconds_per_frame", r.info.frame_dt},
            {"passes", passes},
            {"detail", r.detail},
            {"untimed_within", untimed},
            {"frame", pass(r.frame)},
            {"fps_gpu", r.fps_gpu()},
            {"fps_wall", r.fps_wall()},
            {"real_time_factor_gpu", r.real_time_factor_gpu()},
            {"real_time_factor_wall", r.real_time_factor_wall()}};
    if (const auto& s = r.simulation)
        j["simulation"] = {{"solver", s->solver},
                           {"frames", s->frames},
                           {"steps", s->steps},
                           {"substeps_per_frame", s->substeps_per_frame()},
                           {"most_substeps", s->most_substeps},
                           {"simulated_seconds", s->simulated_seconds},
                           {"wall_seconds", s->wall_seconds},
                           {"iterations_per_step", s->iterations},
                           {"most_iterations", s->most_iterations},
                           {"unconverged_steps", s->unconverged},
                           {"issued_iterations_per_step", s->issued},
                           {"issued_divergence_iterations_per_step", s->issued_divergence},
                           {"divergence_iterations_per_step", s->divergence_iterations},
                           {"most_divergence_iterations", s->most_divergence_iterations},
                           {"unconverged_divergence_steps", s->unconverged_divergence},
                           {"density_error", s->density_error},
                           {"max_density_error", s->max_density_error},
                           {"peak_density_error", s->peak_density_error},
                           {"divergence_error", s->divergence_error},
                           {"least_iteration_dt", s->least_iteration_dt}};
    return j;
}

std::string to_csv(const Report& r) {
    std::ostringstream out;
    out << "device,driver,date,scene,particles,width,height,frames,pass,calls_per_frame,min_ms,median_ms,max_ms,ms_per_call,share,within\n";
    auto line = [&](const PassRow& p) {
        out << csv_field(r.info.renderer) << ',' << csv_field(r.info.driver) << ',' << r.info.date << ','
            << csv_field(r.info.scene) << ',' << r.info.particles << ',' << r.info.width << ',' << r.info.height << ','
            << r.info.frames << ',' << csv_field(p.name) << ',' << p.calls_per_frame << ',' << p.min_ms << ','
            << p.median_ms << ',' << p.max_ms << ',' << p.ms_per_call << ',' << p.share << ','
            << csv_field(p.within) << '\n';
    };
    for (const PassRow& p : r.passes) line(p);
    line(r.frame);
    return out.str();
}

std::string record_csv_header() {
    return "frame,time,substeps,min_dt,max_speed,max_density,iterations,divergence_iterations,most_iterations,"
           "most_divergence_iterations,unconverged,unconverged_divergence,error,divergence_error,max_error,nan,escaped,iteration_dt,"
           "issued,issued_divergence,peak_error,fastest_x,fastest_y,fastest_z,densest_x,densest_y,densest_z\n";
}

std::string record_csv_row(const gpu::StepState& r) {
    auto f = [](std::uint32_t bits) { return std::bit_cast<float>(bits); };
    char line[768];
    std::snprintf(line, sizeof line, "%u,%.7g,%u,%.7g,%.7g,%.7g,%u,%u,%u,%u,%u,%u,%.7g,%.7g,%.7g,%u,%u,%.7g,%u,%u,%.7g,%.7g,%.7g,%.7g,%.7g,%.7g,%.7g\n", r.frame, double(r.time),
                  r.frame_substeps, double(r.frame_min_dt), double(f(r.frame_max_speed)), double(f(r.frame_max_density)),
                  r.iterations.x, r.iterations.y, r.iterations.z, r.iterations.w, r.unconverged.x, r.unconverged.y,
                  double(r.error.x), double(r.error.y), double(r.error.z), r.nan_count, r.escaped_count, double(r.iteration_dt),
                  r.issued, r.issued_divergence, double(f(r.peak_error)), double(r.speed_position.x), double(r.speed_position.y),
                  double(r.speed_position.z), double(r.density_position.x), double(r.density_position.y), double(r.density_position.z));
    return line;
}

std::string utc_now_iso8601() {
    const std::time_t t = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
    std::tm tm{};
    gmtime_r(&t, &tm);
    char buf[32];
    std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
    return buf;
}

void check_writable(const std::filesystem::path& path, const std::string& what) {
    namespace fs = std::filesystem;
    std::error_code ec;
    if (fs::is_directory(path, ec)) throw InputError(what + ": is a folder; name the file to write");
    const fs::path folder = path.parent_path().empty() ? fs::path(".") : path.parent_path();
    if (!fs::exists(folder, ec)) throw InputError(what + ": its folder " + folder.string() + " does not exist");
    if (!fs::is_directory(folder, ec)) throw InputError(what + ": " + folder.string() + " is not a folder");
    fs::path tmp = path;
    tmp += ".tmp";
    std::FILE* f = std::fopen(tmp.c_str(), "wb");
    if (!f) throw InputError(what + ": cannot write the file (" + std::strerror(errno) + ")");
    std::fclose(f);
    fs::remove(tmp, ec);
}

void write_text_file(const std::filesystem::path& path, const std::string& text, const std::string& what) {
    std::filesystem::path tmp = path;
    tmp += ".tmp";
    {
        errno = 0;
        std::ofstream out(tmp, std::ios::binary);
        if (!out) throw InputError(what + ": cannot write the file" + (errno ? std::string(" (") + std::strerror(errno) + ")" : ""));
        out << text;
        if (!out.flush()) throw InputError(what + ": cannot write the file");
    }
    std::error_code ec;
    std::filesystem::rename(tmp, path, ec);
    if (ec) throw InputError(what + ": cannot write the file (" + ec.message() + ")");
}

}  // namespace ranryu::profile
