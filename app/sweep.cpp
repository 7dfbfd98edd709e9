// `ranryu sweep`: the validation cases (engine/validation/cases.h) over case x solver x spacing x
// time-step factor, one row a run, for the speed/accuracy chart and the stability map
// (scripts/sweep-charts.py); and the scene cases, "scene:NAME", the bundled SPH scenes run as they
// are for --seconds, from whose rows scripts/scene-settings.py chooses each scene's cheapest sound
// setting (docs/SWEEP.md). Rows are written after every run and a second invocation skips the rows
// its folder already holds, so a sweep resumes; --shard splits the rows between jobs.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "commands.h"
#include "core/error.h"
#include "frame/stop.h"
#include "gl/context.h"
#include "profile/report.h"
#include "sim/guard.h"
#include "validation/cases.h"

namespace ranryu::app {
namespace {

constexpr double kEnergyGain = 0.01;   // see run_row()
constexpr float kSceneSeconds = 10.0f;  // a scene case's simulated time without --seconds

struct Row {
    std::string case_name, solver;
    float spacing = 0.0f, factor = 1.0f;
    std::string key() const {
        char buf[160];
        std::snprintf(buf, sizeof buf, "%s/%s/%.6g/%.6g", case_name.c_str(), solver.c_str(), spacing, factor);
        return buf;
    }
};

// The grid in the order --list prints and --shard counts: case, solver, spacing, factor.
std::vector<Row> grid(const Options& o) {
    std::vector<std::string> cases = o.cases, solvers = o.solvers;
    std::vector<float> spacings = o.spacings, factors = o.factors;
    if (o.quick) {
        if (cases.empty()) cases = {"dam-break", "hydrostatic"};
        if (spacings.empty()) spacings = {0.04f, 0.025f};
        if (factors.empty()) factors = {1.0f, 10.0f};   // WCSPH at 10 leaves the tank within a frame
        if (solvers.empty()) solvers = {"dfsph", "wcsph"};
    }
    if (cases.empty()) cases = {"dam-break", "hydrostatic", "standing-wave"};
    if (solvers.empty()) solvers = {"dfsph", "wcsph", "pbf"};
    if (factors.empty()) factors = {0.5f, 1.0f, 1.5f, 2.0f};
    std::vector<Row> rows;
    for (const std::string& c : cases) {
        std::vector<float> dx = spacings;
        if (dx.empty()) {
            // A validation case at its own spacing and half of it; a scene case at its own: the
            // spacing its file ships with is the one its settings are chosen for.
            const float own = validation::case_scene(c).spacing;
            dx = validation::is_scene_case(c) ? std::vector<float>{own} : std::vector<float>{own, 0.5f * own};
        }
        for (const std::string& s : solvers)
            for (float d : dx)
                for (float f : factors) rows.push_back({c, s, d, f});
    }
    return rows;
}

// The rows a folder already holds (none when it has no sweep.json); a file that is not a sweep's is
// bad input, and is left as it is.
nlohmann::json read_rows(const std::filesystem::path& file) {
    if (!std::filesystem::exists(file)) return nlohmann::json::array();
    std::ifstream in(file);
    nlohmann::json j;
    try {
        in >> j;
    } catch (const std::exception& e) {
        throw InputError(file.string() + ": not a sweep's rows (" + e.what() + "); move it away or choose another --out");
    }
    if (!j.is_object() || !j.contains("rows") || !j["rows"].is_array())
        throw InputError(file.string() + ": not a sweep's rows (no \"rows\" array); move it away or choose another --out");
    for (const auto& r : j["rows"])
        if (!r.is_object() || !r.contains("key") || !r["key"].is_string())
            throw InputError(file.string() + ": a row without its \"key\"; move it away or choose another --out");
    return j["rows"];
}

// The CSV's columns, in order; a field a row lacks is left empty.
const std::vector<std::string> kColumns = {"key", "case", "solver", "spacing", "factor", "particles", "status", "error", "error_max",
                                           "error_name", "mean_density_deviation", "max_density_deviation", "energy_drift",
                                           "gpu_ms_per_simulated_second", "simulated_seconds", "wall_seconds", "steps",
                                           "failure_frame", "failure_time", "failure_cause", "failure_message", "device",
                                           "seconds", "mean_density_deviation_peak", "mean_density_deviation_peak_time",
                                           "mean_density_deviation_average", "energy_check", "decay_rate", "guard_spikes"};

std::string csv_field(const nlohmann::json& v) {
    if (v.is_null()) return "";
    std::string s = v.is_string() ? v.get<std::string>() : v.dump();
    if (s.find_first_of(",\"\n") == std::string::npos) return s;
    std::string q = "\"";
    for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
    return q + "\"";
}

// Both files, each through a temporary and a rename: an interrupted write leaves the last whole one.
void write_rows(const std::filesystem::path& dir, const nlohmann::json& rows) {
    profile::write_text_file((dir / "sweep.json.tmp").string(), nlohmann::json{{"rows", rows}}.dump(1) + "\n", "--out " + dir.string());
    std::ostringstream csv;
    for (std::size_t k = 0; k < kColumns.size(); ++k) csv << (k ? "," : "") << kColumns[k];
    csv << "\n";
    for (const auto& r : rows) {
        for (std::size_t k = 0; k < kColumns.size(); ++k) csv << (k ? "," : "") << csv_field(r.value(kColumns[k], nlohmann::json()));
        csv << "\n";
    }
    profile::write_text_file((dir / "sweep.csv.tmp").string(), csv.str(), "--out " + dir.string());
    std::filesystem::rename(dir / "sweep.json.tmp", dir / "sweep.json");
    std::filesystem::rename(dir / "sweep.csv.tmp", dir / "sweep.csv");
}

template <class Result>
void put_stats(nlohmann::json& j, const Result& r) {
    j.update({{"particles", r.particles},
              {"mean_density_deviation", r.stats.mean_density_deviation},
              {"max_density_deviation", r.stats.max_density_deviation},
              {"energy_drift", r.stats.energy_drift},
              {"guard_spikes", r.stats.guard_spikes},
              {"gpu_ms_per_simulated_second", r.stats.gpu_ms_per_simulated_second},
              {"simulated_seconds", r.stats.simulated_seconds},
              {"wall_seconds", r.seconds},
              {"steps", r.steps}});
}

// One run: its row, stable or not. Bad input and interrupts propagate. `seconds`: a scene case's
// simulated time.
nlohmann::json run_row(const Row& row, const Options& o, const shader::FileSource& shaders, const std::string& device, float seconds) {
    scene::Scene scene = scene::with_spacing(validation::case_scene(row.case_name), row.spacing, "--spacings");
    scene.sph.solver = scene::parse_solver(row.solver, "--solvers");
    scene.sph.cfl *= row.factor;             // every bound on the step scales (the frame's length stays one)
    scene.sph.dfsph_cfl *= row.factor;       // DFSPH's own (D8); 0, DFSPH on sph.cfl, stays 0
    scene.sph.force_factor *= row.factor;
    scene.sph.max_time_step *= row.factor;
    // PBF's step is fixed, frame_dt / substeps (docs/PBF.md (P1)): the factor multiplies it, so the
    // substeps a frame are divided by it (at least one), and the iterations a substep stay.
    scene::PbfSettings& pbf = scene.sph.pbf;
    pbf.substeps = std::max(1, int(std::lround(double(pbf.substeps) / double(row.factor))));
    nlohmann::json j = {{"key", row.key()}, {"case", row.case_name}, {"solver", row.solver}, {"spacing", row.spacing},
                        {"factor", row.factor}, {"cfl", scene.sph.cfl}, {"force_factor", scene.sph.force_factor}, {"max_time_step", scene.sph.max_time_step}, {"device", device}, {"date", profile::utc_now_iso8601()}};
    if (scene.sph.solver == scene::Solver::pbf) j.update({{"pbf_substeps", pbf.substeps}, {"pbf_iterations", pbf.iterations}});
    if (scene.sph.solver == scene::Solver::dfsph && scene.sph.dfsph_cfl > 0.0f) j["dfsph_cfl"] = scene.sph.dfsph_cfl;   // (D8): in force over cfl
    // A closed system under gravity only loses energy (viscosity, impacts), so a gain is an
    // instability; the turbulence force does work on the fluid, and there a gain says nothing.
    const bool energy_checked = !scene.turbulence.enabled();
    j["energy_check"] = energy_checked ? "gain above 1 % is unstable" : "none: the turbulence force does work on the fluid";
    if (validation::is_scene_case(row.case_name)) j["seconds"] = seconds;
    frame::Progress progress = make_progress(o, "ranryu sweep " + row.key());
    try {
        if (row.case_name == "dam-break") {
            const validation::DamBreakResult r = validation::dam_break(scene, shaders, &progress);
            put_stats(j, r);
            j.update({{"error", r.rms_error}, {"error_max", r.max_error}, {"error_name", "surge front rms error in Z (Martin & Moyce 1952)"}});
        } else if (validation::is_scene_case(row.case_name)) {
            // No reference: the error is the scene's own accuracy, its worst frame's mean compression.
            const validation::SceneRunResult r = validation::scene_run(scene, shaders, seconds, &progress);
            put_stats(j, r);
            j.update({{"error", r.peak_mean_compression}, {"error_max", r.stats.max_density_deviation},
                      {"error_name", "largest mean compression over the frames (no reference; max density deviation as error_max)"},
                      {"mean_density_deviation_peak", r.peak_mean_compression}, {"mean_density_deviation_peak_time", r.peak_time},
                      {"mean_density_deviation_average", r.average_mean_compression}});
        } else if (validation::is_impact_case(row.case_name)) {
            const validation::ImpactPressureResult r = validation::impact_case(row.case_name, scene, shaders, &progress);
            put_stats(j, r);
            // The sensors' rms over the case's window after the impact, their mean the error and the
            // largest the error_max (docs/VALIDATION.md "Impact pressure").
            double sum = 0.0, most = 0.0;
            nlohmann::json sensors = nlohmann::json::object();
            for (const auto& s : r.sensors) {
                sum += s.rms_error, most = std::max(most, s.rms_error);
                sensors[s.name] = {{"rms_error", s.rms_error}, {"mean", s.mean_simulated}, {"mean_experiment", s.mean_measured},
                                   {"onset", s.onset_simulated ? nlohmann::json(*s.onset_simulated) : nlohmann::json()},
                                   {"onset_experiment", s.onset_measured ? nlohmann::json(*s.onset_measured) : nlohmann::json()}};
            }
            j.update({{"error", sum / double(r.sensors.size())},
                      {"error_max", most},
                      {"error_name", "pressure's rms error / rho0 g H after the impact, mean over the sensors (" + r.source.substr(0, r.source.find(',')) + ")"},
                      {"sensors", sensors}});
        } else if (row.case_name == "standing-wave") {
            const validation::StandingWaveResult r = validation::standing_wave(scene, shaders, &progress);
            put_stats(j, r);
            j.update({{"error", r.period_error}, {"error_max", r.period_error},
                      {"error_name", "standing wave's period error |T - T_linear| / T_linear"}, {"decay_rate", r.decay_rate}});
        } else {   // hydrostatic (--cases admits no other: validation::case_scene)
            const validation::HydrostaticResult r = validation::hydrostatic(scene, shaders, 1.0, &progress);
            put_stats(j, r);
            j.update({{"error", r.max_error}, {"error_max", r.floor_error},
                      {"error_name", "interior pressure error / rho0 g H (floor layer's as error_max)"}});
        }
        progress.finish();
        j["status"] = "stable";
        // A run that made more than kEnergyGain of its start went unstable though no guard bound
        // fired (where the energy is checked, above).
        if (energy_checked && j["energy_drift"].get<double>() > kEnergyGain) {
            char msg[200];
            std::snprintf(msg, sizeof msg, "energy gain: the fluid's energy grew by %.1f %% over %.2f s (bound %.0f %%)",
                          100.0 * j["energy_drift"].get<double>(), j["simulated_seconds"].get<double>(), 100.0 * kEnergyGain);
            j.update({{"status", "unstable"}, {"failure_frame", nullptr}, {"failure_time", j["simulated_seconds"]},
                      {"failure_cause", "energy gain"}, {"failure_message", msg}});
        }
    } catch (const validation::NoMeasurement& e) {
        // Sound by the guard, but the case's flow gave no number to compare: neither a point on the
        // accuracy chart nor a stable cell of the map.
        progress.finish();
        j.update({{"status", "no result"},
                  {"particles", scene.particle_count()},
                  {"failure_frame", nullptr},
                  {"failure_time", nullptr},
                  {"failure_cause", "no measurement"},
                  {"failure_message", e.what()}});
    } catch (const sim::UnstableError& e) {
        progress.finish();
        j.update({{"status", "unstable"},
                  {"particles", scene.particle_count()},
                  {"failure_frame", e.finding.frame},
                  {"failure_time", e.finding.time},
                  {"failure_cause", e.finding.criterion},
                  {"failure_message", e.finding.message()}});
    }
    return j;
}

}  // namespace

int sweep(const Options& o) {
    const std::vector<Row> rows = grid(o);
    const std::filesystem::path dir = o.out.empty() ? std::filesystem::path() : std::filesystem::path(o.out);
    nlohmann::json done = dir.empty() ? nlohmann::json::array() : read_rows(dir / "sweep.json");
    std::map<std::string, nlohmann::json> finished;
    for (const auto& r : done) finished[r["key"].get<std::string>()] = r;
    std::vector<std::size_t> mine;
    for (std::size_t k = 0; k < rows.size(); ++k)
        if (int(k % std::size_t(o.shard_count)) == o.shard_index - 1) mine.push_back(k);
    // A scene case's row is done only if it ran as long as asked: a folder of 2-second rows does not
    // stand for a 10-second sweep. Checked before any run.
    const float seconds = o.seconds.value_or(kSceneSeconds);
    for (std::size_t k : mine) {
        const auto f = finished.find(rows[k].key());
        if (f == finished.end() || !validation::is_scene_case(rows[k].case_name)) continue;
        const double ran = f->second.value("seconds", -1.0);
        if (std::abs(ran - double(seconds)) > 1e-6 * double(seconds)) {
            char msg[400];
            std::snprintf(msg, sizeof msg, "%s: row %s ran %g simulated seconds, and --seconds asks for %g; choose another --out",
                          (dir / "sweep.json").c_str(), rows[k].key().c_str(), ran, double(seconds));
            throw InputError(msg);
        }
    }
    if (o.list) {
        for (std::size_t k : mine) std::printf("%zu %s%s\n", k, rows[k].key().c_str(), finished.count(rows[k].key()) ? " (done)" : "");
        return 0;
    }
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec || !std::filesystem::is_directory(dir)) throw InputError("--out " + o.out + ": cannot make the folder (" + ec.message() + ")");
    // The rows' files, before the first row runs (each is written as FILE.tmp, then renamed).
    for (const char* name : {"sweep.json", "sweep.csv"}) profile::check_writable(dir / name, "--out " + o.out + " (" + name + ")");
    const shader::FileSource shaders = shader_source(o);
    auto ctx = headless(o);
    const std::string device = ctx->info().renderer + " | " + ctx->info().version;
    std::size_t ran = 0, skipped = 0, unstable = 0, n = 0;
    for (std::size_t k : mine) {
        ++n;
        if (finished.count(rows[k].key())) {
            ++skipped;
            continue;
        }
        const nlohmann::json row = run_row(rows[k], o, shaders, device, seconds);
        done.push_back(row);
        write_rows(dir, done);
        ++ran;
        const bool stable = row["status"] == "stable";
        if (!stable) ++unstable;
        char what[400];
        if (!stable) std::snprintf(what, sizeof what, "%s", row["failure_message"].get<std::string>().c_str());
        else
            std::snprintf(what, sizeof what, "%s %.6g, %.6g GPU ms per simulated s, %llu steps",
                          validation::is_scene_case(rows[k].case_name) ? "largest mean compression" : "error", row["error"].get<double>(),
                          row["gpu_ms_per_simulated_second"].get<double>(), row["steps"].get<unsigned long long>());
        std::printf("sweep [%zu/%zu] %s: %s\n", n, mine.size(), rows[k].key().c_str(), what);
        std::fflush(stdout);
    }
    std::printf("sweep: %zu run (%zu unstable), %zu already done, rows in %s\n", ran, unstable, skipped, (dir / "sweep.json").c_str());
    return 0;
}

}  // namespace ranryu::app
