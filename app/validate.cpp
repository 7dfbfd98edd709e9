// `ranryu validate CASE`: runs a published experiment or an analytic case headless and prints the
// simulation next to the reference with the error (engine/validation/cases.h); --json for machines.
#include <cstdio>

#include <nlohmann/json.hpp>

#include "commands.h"
#include "core/error.h"
#include "gl/context.h"
#include "profile/report.h"
#include "scene/scene.h"
#include "validation/cases.h"

namespace ranryu::app {

int validate(const Options& o) {
    if (o.case_name != "dam-break" && o.case_name != "hydrostatic" && o.case_name != "standing-wave" && o.case_name != "impact-pressure" &&
        o.case_name != "obstacle-impact")
        throw InputError("validate: unknown case \"" + o.case_name + "\" (cases: " + validation::kCaseList + ")");
    const scene::Scene scene = with_options(o.scene_given ? scene::load(o.scene) : validation::case_scene(o.case_name), o);
    validation::check_case_scene(o.case_name, scene);   // before the GL context is made
    check_report_files(o);   // --json, before the case runs
    frame::Progress progress = make_progress(o, "ranryu validate " + o.case_name);
    const shader::FileSource shaders = shader_source(o);
    auto ctx = headless(o);
    nlohmann::json j = {{"case", o.case_name},
                        {"device", ctx->info().renderer},
                        {"driver", ctx->info().version},
                        {"date", profile::utc_now_iso8601()},
                        {"spacing", scene.spacing},
                        {"solver", scene::solver_name(scene.sph.solver)},
                        {"scene_origin", scene.origin},
                        {"boundary_viscosity", scene.sph.boundary_viscosity}};
    if (o.case_name == "dam-break") {
        const validation::DamBreakResult r = validation::dam_break(scene, shaders, &progress);
        progress.finish();
        std::printf("dam-break (Martin & Moyce 1952, n^2 = 2): a = %.3f m, spacing %.4f m (a/dx = %.1f), %zu particles\n", r.a,
                    r.spacing, r.a / r.spacing, r.particles);
        std::printf("%8s %10s %10s %10s\n", "T", "Z exp", "Z sim", "diff");
        for (const auto& c : r.compared) std::printf("%8.2f %10.3f %10.3f %+10.3f\n", c.t, c.measured, c.simulated, c.simulated - c.measured);
        std::printf("surge front error: rms %.3f, max %.3f (in Z = z/a)\n", r.rms_error, r.max_error);
        std::printf("%s: %llu steps in %.1f s of wall time\n", scene::solver_name(scene.sph.solver),
                    static_cast<unsigned long long>(r.steps), r.seconds);
        nlohmann::json cmp = nlohmann::json::array(), sim = nlohmann::json::array();
        for (const auto& c : r.compared) cmp.push_back({{"T", c.t}, {"Z_experiment", c.measured}, {"Z_simulation", c.simulated}});
        for (const auto& [t, z] : r.simulated) sim.push_back({{"T", t}, {"Z", z}});
        j.update({{"a", r.a},
                  {"particles", r.particles},
                  {"source", "Martin & Moyce 1952, Phil. Trans. R. Soc. A 244, Tables 2 and 6"},
                  {"compared", cmp},
                  {"simulation", sim},
                  {"rms_error", r.rms_error},
                  {"max_error", r.max_error},
                  {"steps", r.steps},
                  {"wall_seconds", r.seconds}});
    } else if (validation::is_impact_case(o.case_name)) {
        const validation::ImpactPressureResult r = validation::impact_case(o.case_name, scene, shaders, &progress);
        progress.finish();
        std::printf("%s (%s): H = %.3f m, spacing %.4f m (H/dx = %.1f), %zu particles\n", o.case_name.c_str(), r.source.c_str(), r.height,
                    r.spacing, r.height / r.spacing, r.particles);
        std::printf("p/(rho0 g H) on the face struck (x = %.4f m); impact: first T at %.2f; compared: T in [%.1f, %.1f]\n", r.face,
                    validation::kImpactOnset, r.window[0], r.window[1]);
        std::printf("%6s %8s %18s %18s %22s %10s\n", "sensor", "z (mm)", "impact T exp/sim", "peak exp/sim", "window mean exp/sim", "rms diff");
        auto onset = [](const std::optional<double>& t) { return t ? *t : -1.0; };
        for (const auto& s : r.sensors)
            std::printf("%6s %8.1f %8.3f/%-9.3f %8.3f/%-9.3f %10.3f/%-11.3f %10.3f\n", s.name.c_str(), 1000.0 * s.z, onset(s.onset_measured),
                        onset(s.onset_simulated), s.peak_measured, s.peak_simulated, s.mean_measured, s.mean_simulated, s.rms_error);
        std::printf("(an impact T of -1: the reading never reached %.2f)\n", validation::kImpactOnset);
        std::printf("%s: %llu steps in %.1f s of wall time\n", scene::solver_name(scene.sph.solver),
                    static_cast<unsigned long long>(r.steps), r.seconds);
        nlohmann::json sensors = nlohmann::json::array();
        for (const auto& s : r.sensors) {
            nlohmann::json sim = nlohmann::json::array();
            for (const auto& [t, p] : s.simulated) sim.push_back({{"T", t}, {"p", p}});
            sensors.push_back({{"name", s.name},
                               {"z", s.z},
                               {"onset_experiment", s.onset_measured ? nlohmann::json(*s.onset_measured) : nlohmann::json()},
                               {"onset_simulation", s.onset_simulated ? nlohmann::json(*s.onset_simulated) : nlohmann::json()},
                               {"peak_experiment", s.peak_measured},
                               {"peak_simulation", s.peak_simulated},
                               {"window_mean_experiment", s.mean_measured},
                               {"window_mean_simulation", s.mean_simulated},
                               {"window_rms_error", s.rms_error},
                               {"window_compared", s.compared},
                               {"simulation", sim}});
        }
        j.update({{"height", r.height},
                  {"particles", r.particles},
                  {"source", r.source},
                  {"face_x", r.face},
                  {"sample_offset_frames", r.sample_offset},
                  {"onset_level", validation::kImpactOnset},
                  {"window", {r.window[0], r.window[1]}},
                  {"sensors", sensors},
                  {"steps", r.steps},
                  {"wall_seconds", r.seconds}});
    } else if (o.case_name == "standing-wave") {
        const validation::StandingWaveResult r = validation::standing_wave(scene, shaders, &progress);
        progress.finish();
        std::printf("standing-wave: L = %.3f m, H = %.3f m, A = %.4f m, spacing %.4f m, %zu particles\n", r.length, r.depth, r.amplitude,
                    r.spacing, r.particles);
        std::printf("period: %.4f s simulated (over %d half periods), %.4f s linear theory: error %.4f\n", r.period, r.half_periods,
                    r.period_theory, r.period_error);
        std::printf("decay of the mode: %.4f /s simulated, %.4f /s the bulk's 2 nu k^2 (walls add more)\n", r.decay_rate, r.decay_theory);
        std::printf("%s: %llu steps in %.1f s of wall time\n", scene::solver_name(scene.sph.solver),
                    static_cast<unsigned long long>(r.steps), r.seconds);
        nlohmann::json series = nlohmann::json::array();
        for (const auto& [t, m] : r.moment) series.push_back({{"t", t}, {"moment", m}});
        j.update({{"length", r.length}, {"depth", r.depth}, {"amplitude", r.amplitude}, {"particles", r.particles},
                  {"period", r.period}, {"period_theory", r.period_theory}, {"period_error", r.period_error},
                  {"half_periods", r.half_periods}, {"decay_rate", r.decay_rate}, {"decay_theory", r.decay_theory},
                  {"moment", series}, {"steps", r.steps}, {"wall_seconds", r.seconds}});
    } else {
        const validation::Relaxation relax = o.relax ? validation::hydrostatic_relaxation(scene) : validation::Relaxation{};
        const validation::HydrostaticResult r =
            validation::hydrostatic(scene, shaders, o.settle.value_or(1.0f), relax, &progress, o.average.value_or(0.5f));
        progress.finish();
        const double settle = o.settle.value_or(1.0f);
        std::printf("hydrostatic: H = %.3f m, spacing %.4f m, %zu particles, averaged over %.4g-%.4g s%s\n", r.height, r.spacing, r.particles,
                    settle, settle + r.average_seconds, o.relax ? " after the relaxed start" : " from the lattice");
        std::printf("%8s %12s %12s %8s %10s %10s\n", "z (m)", "p sim (Pa)", "rho g (H-z)", "count", "rms (m/s)", "vertical");
        for (const auto& l : r.layers) std::printf("%8.4f %12.2f %12.2f %8d %10.4f %10.4f\n", l.z, l.pressure, l.reference, l.particles, l.rms_speed, l.rms_vertical);
        std::printf("pressure error in the interior (a kernel support from floor and surface): max %.4f of rho0 g H; spurious speed: max %.4f m/s, rms %.4f m/s\n",
                    r.max_error, r.max_speed, r.rms_speed);
        std::printf("rms speed averaged over the %.4g s: %.4f m/s\n", r.average_seconds, r.mean_rms_speed);
        std::printf("floor layer: %.4f of rho0 g H; away from the side walls (a kernel support): interior %.4f, floor layer %.4f\n",
                    r.floor_error, r.core_error, r.core_floor_error);
        std::printf("interior over pairs of layers (two spacings thick, a layer-to-layer alternation cancelled): max %.4f of rho0 g H; "
                    "the floor's pair (the floor layer and the next): %.4f\n",
                    r.pair_error, r.floor_pair_error);
        std::printf("%s: %llu steps in %.1f s of wall time\n", scene::solver_name(scene.sph.solver),
                    static_cast<unsigned long long>(r.steps), r.seconds);
        if (r.windows.size() > 1) {
            std::printf("each half second alone (from the end of the settling), interior / floor layer of rho0 g H:");
            for (const auto& w : r.windows) std::printf(" %.2f s: %.4f / %.4f;", w.start, w.max_error, w.floor_error);
            std::printf("\n");
        }
        if (o.relax) {
            const double last_rms = r.relax_rms_speeds.empty() ? 0.0 : r.relax_rms_speeds.back();
            std::printf("relaxed start: %d frames at rest (%llu steps, %.1f s of wall time), last frame from rest: rms %.5f m/s, max %.4f m/s; bound rms %.5f m/s: %s\n",
                    r.relax_frames, static_cast<unsigned long long>(r.relax_steps), r.relax_seconds, last_rms, r.relax_max_speed,
                    relax.rms_speed, r.relaxed ? "reached" : "NOT reached");
        }
        nlohmann::json layers = nlohmann::json::array();
        for (const auto& l : r.layers) layers.push_back({{"z", l.z}, {"pressure", l.pressure}, {"reference", l.reference}, {"particles", l.particles}, {"rms_speed", l.rms_speed}, {"rms_vertical", l.rms_vertical}});
        nlohmann::json windows = nlohmann::json::array();
        for (const auto& w : r.windows)
            windows.push_back({{"start", w.start}, {"max_error_over_rho_g_H", w.max_error}, {"floor_error_over_rho_g_H", w.floor_error}});
        j.update({{"height", r.height},
                  {"particles", r.particles},
                  {"layers", layers},
                  {"max_error_over_rho_g_H", r.max_error},
                  {"floor_error_over_rho_g_H", r.floor_error},
                  {"core_error_over_rho_g_H", r.core_error},
                  {"core_floor_error_over_rho_g_H", r.core_floor_error},
                  {"pair_error_over_rho_g_H", r.pair_error},
                  {"floor_pair_error_over_rho_g_H", r.floor_pair_error},
                  {"max_speed", r.max_speed},
                  {"rms_speed", r.rms_speed},
                  {"mean_rms_speed", r.mean_rms_speed},
                  {"settle_seconds", settle},
                  {"average_seconds", r.average_seconds},
                  {"windows", windows},
                  {"steps", r.steps},
                  {"wall_seconds", r.seconds},
                  {"relaxation", {{"frames", r.relax_frames},
                                  {"max_frames", relax.max_frames},
                                  {"steps", r.relax_steps},
                                  {"rms_speed_bound", relax.rms_speed},
                                  {"rms_speeds", r.relax_rms_speeds},
                                  {"last_max_speed", r.relax_max_speed},
                                  {"reached", r.relaxed},
                                  {"wall_seconds", r.relax_seconds}}}});
    }
    if (!o.json.empty()) profile::write_text_file(o.json, j.dump(2) + "\n", "--json " + o.json);
    return 0;
}

}  // namespace ranryu::app
