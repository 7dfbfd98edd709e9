#include "commands.h"

#include "simulation_log.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <memory>

#include <glm/gtc/constants.hpp>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "frame/checkpoint.h"
#include "frame/loop.h"
#include "frame/pipeline.h"
#include "frame/progress.h"
#include "frame/stop.h"
#include "gl/context.h"
#include "gl/faults.h"
#include "profile/report.h"
#include "record/mesh_export.h"
#include "record/particle_export.h"
#include "record/png.h"
#include "record/recorder.h"
#include "record/video.h"
#include "scene/keys.h"
#include "scene/scene.h"
#include "shader/source.h"
#include "sim/guard.h"
#include "version.h"
#ifdef RANRYU_HAVE_IMGUI
#include "overlay.h"
#endif

namespace ranryu::app {

#ifdef NDEBUG
bool debug_context(const Options& o) { return o.gl_debug; }
#else
bool debug_context(const Options&) { return true; }
#endif

shader::FileSource shader_source(const Options& o) {
    std::string dir = o.shader_dir;
    if (dir.empty())
        if (const char* env = std::getenv("RANRYU_SHADER_DIR")) dir = env;
    if (dir.empty()) return shader::FileSource::embedded();
    if (!std::filesystem::is_directory(dir)) throw InputError("--shader-dir " + dir + ": not a folder");
    return shader::FileSource::directory(dir);
}

std::optional<render::Shading> shading(const Options& o) {
    if (o.shading.empty()) return std::nullopt;
    return render::parse_shading(o.shading);
}

glm::ivec2 image_size(const Options& o, const scene::Scene& s) {
    return {o.width.value_or(s.width), o.height.value_or(s.height)};
}


profile::RunInfo run_info(const gl::DeviceInfo& d, const frame::Pipeline& p, int frames, int warmup) {
    profile::RunInfo info;
    info.renderer = d.renderer;
    info.driver = d.version;
    info.platform = d.platform;
    info.date = profile::utc_now_iso8601();
    info.scene = p.scene().name;
    info.particles = p.particle_count();
    info.width = p.target().width();
    info.height = p.target().height();
    info.frames = frames;
    info.warmup = warmup;
    const scene::Scene& s = p.scene();
    info.substeps = s.model != scene::Model::sph ? s.substeps() : s.sph.solver == scene::Solver::pbf ? s.sph.pbf.substeps : 0;
    info.frame_dt = p.scene().frame_dt;
    return info;
}

namespace {

// "device memory: estimated X MiB, allocated Y MiB ..." and its JSON.
std::string memory_line(const frame::MemoryUse& m) {
    std::string line = "device memory: estimated " + frame::mib(m.estimate.total()) + ", allocated " + frame::mib(m.allocated) +
                       " (peak " + frame::mib(m.peak) + " at start-up), available " +
                       (m.device.available ? frame::mib(*m.device.available) : std::string("unknown")) + " (" + m.device.source + ")\n";
    for (const frame::MemoryPart& p : m.estimate.parts) line += "  " + p.name + ": " + frame::mib(p.bytes) + "\n";
    return line;
}
nlohmann::json memory_json(const frame::MemoryUse& m) {
    nlohmann::json parts = nlohmann::json::object();
    for (const frame::MemoryPart& p : m.estimate.parts) parts[p.name] = p.bytes;
    return {{"estimated_bytes", m.estimate.total()}, {"allocated_bytes", m.allocated}, {"peak_bytes", m.peak},
            {"available_bytes", m.device.available ? nlohmann::json(*m.device.available) : nlohmann::json(nullptr)},
            {"source", m.device.source}, {"parts", parts}};
}


// The guard's spikes that passed (sim/guard.h): a line for the report, and its JSON; nothing when
// there were none (or no SPH).
std::string guard_spikes_line(const frame::Pipeline& p, nlohmann::json& extra) {
    if (!p.simulation()) return {};
    const sim::Guard& g = p.simulation()->fluid().guard();
    if (g.spikes() == 0) return {};
    const sim::Instability& worst = *g.largest_spike();
    char line[400];
    std::snprintf(line, sizeof line,
                  "guard: %d frame(s) past a bound, each followed by one within it (spikes, not stopped; sim/guard.h); the "
                  "largest at frame %llu, t = %.4f s: %s (%s)\n",
                  g.spikes(), static_cast<unsigned long long>(worst.frame), worst.time, worst.criterion.c_str(),
                  worst.detail().c_str());
    extra["guard_spikes"] = {{"frames", g.spikes()},
                             {"largest", {{"frame", worst.frame}, {"time", worst.time}, {"criterion", worst.criterion},
                                          {"value", worst.value}, {"limit", worst.limit}}}};
    if (worst.position) extra["guard_spikes"]["largest"]["position"] = {worst.position->x, worst.position->y, worst.position->z};
    return line;
}
}  // namespace

void print_device(const gl::DeviceInfo& d) {
    std::printf("ranryu %s | %s\n", RANRYU_VERSION, d.line().c_str());
    if (!d.timer_queries) std::printf("ranryu: this context has no timer queries; timings will read 0\n");
    if (!d.robust) std::printf("ranryu: this context is not robust: a GPU reset would go unreported (gl/faults.h)\n");
    std::fflush(stdout);
}

// Headless context, with the debug callback in Debug builds or with --gl-debug.
std::unique_ptr<gl::HeadlessContext> headless(const Options& o, bool announce) {
    const bool debug = debug_context(o);
    auto ctx = std::make_unique<gl::HeadlessContext>(debug);
    if (debug) gl::install_debug_callback();
    gl::set_error_checks(debug);   // glGetError after every pass (gl/faults.h)
    if (announce) print_device(ctx->info());
    return ctx;
}

scene::Scene load_scene(const Options& o) { return with_options(scene::load(o.scene), o); }

// The build a checkpoint belongs to: the version and the commit (frame/checkpoint.h).
std::string build_id() { return std::string(RANRYU_VERSION) + " " + app::commit(); }

void check_report_files(const Options& o) {
    for (const auto& [option, path] : {std::pair{"--records", &o.records}, std::pair{"--json", &o.json}, std::pair{"--csv", &o.csv}})
        if (!path->empty()) profile::check_writable(*path, std::string(option) + " " + *path);
    if (!o.checkpoint.empty()) frame::check_checkpoint_path(o.checkpoint, "--checkpoint " + o.checkpoint);
}

// --resume FILE: the checkpoint's header (its scene is the run's; frame/checkpoint.h). The scene
// options would contradict it, and an existing --records file is the earlier run's: refused. And
// the report files and --checkpoint FILE: checked writable first (check_report_files).
std::optional<frame::CheckpointInfo> resumed_run(const Options& o) {
    check_report_files(o);
    if (o.resume.empty()) return std::nullopt;
    const std::string what = "--resume " + o.resume;
    if (o.scene_given) throw InputError(what + ": the run goes on with the checkpoint's scene; drop --scene");
    if (o.spacing) throw InputError(what + ": the run goes on at the checkpoint's spacing; drop --spacing");
    if (!o.solver.empty()) throw InputError(what + ": the run goes on with the checkpoint's solver; drop --solver");
    std::error_code ec;
    if (!o.records.empty() && std::filesystem::exists(o.records, ec))
        throw InputError("--records " + o.records + ": exists (the earlier run's records?); a resumed run writes its own: name another file");
    return frame::read_checkpoint(o.resume, what, build_id());
}

// A resumed record goes on in the folder of the run it continues: one whose run.json names another
// scene or particle count holds another run, and the resumed frames would be mixed into it. (A folder
// without run.json, or with one that cannot be read, is left to prepare_output's checks.)
void check_resumed_folder(const std::filesystem::path& out, const frame::CheckpointInfo& resumed) {
    std::ifstream in(out / "run.json");
    if (!in) return;
    const nlohmann::json j = nlohmann::json::parse(in, nullptr, /*allow_exceptions=*/false);
    if (!j.is_object() || !j.contains("scene") || !j.contains("particles")) return;
    const std::string scene = j["scene"].is_string() ? j["scene"].get<std::string>() : "";
    const bool same_count = j["particles"].is_number_unsigned() && j["particles"].get<std::uint64_t>() == resumed.particles;
    if (scene != resumed.scene.name || !same_count)
        throw InputError("--out " + out.string() + ": holds a run of " + (scene.empty() ? std::string("another scene") : "scene " + scene) + " (" +
                         j["particles"].dump() + " particles), and the checkpoint is of scene " + resumed.scene.name + " (" +
                         std::to_string(resumed.particles) + " particles); choose another folder");
}

// --checkpoint FILE at the end of a run (after the drain): writes it and says so, or returns why not.
std::string write_checkpoint(const Options& o, frame::Pipeline& pipeline) {
    if (o.checkpoint.empty()) return {};
    try {
        frame::write_checkpoint(pipeline, o.checkpoint, "--checkpoint " + o.checkpoint, build_id());
    } catch (const InputError& e) {
        return e.what();
    }
    std::printf("wrote the checkpoint %s (frame %llu, t = %.4f s): go on with --resume %s\n", o.checkpoint.c_str(),
                static_cast<unsigned long long>(pipeline.frames()), pipeline.simulated_time(), o.checkpoint.c_str());
    return {};
}

frame::Progress make_progress(const Options& o, const std::string& label) {
    double interval = 10.0;
    if (const char* env = std::getenv("RANRYU_PROGRESS_SECONDS")) {
        char* end = nullptr;
        interval = std::strtod(env, &end);
        if (!*env || *end || !(interval >= 0.0 && interval <= 86400.0))
            throw InputError(std::string("RANRYU_PROGRESS_SECONDS=") + env + ": expected seconds in [0, 86400]");
    }
    return frame::Progress(label, frame::Progress::mode_for(stderr, o.quiet), stderr, interval);
}

scene::Scene with_options(scene::Scene s, const Options& o) {
    if (o.spacing) s = scene::with_spacing(s, *o.spacing, "--spacing");
    if (!o.solver.empty()) {
        if (s.model != scene::Model::sph)
            throw InputError("--solver " + o.solver + ": scene " + s.name + " uses the ballistic model, which has no pressure solver");
        s.sph.solver = scene::parse_solver(o.solver, "--solver");
    }
    return s;
}

int scenes(const Options& o) {
    if (o.schema) return std::fputs(scene::json_schema().c_str(), stdout), 0;
    if (o.markdown) return std::fputs(scene::markdown().c_str(), stdout), 0;
    for (const scene::BundledScene& s : scene::bundled()) {
        std::printf("%-20s %s\n", s.name.c_str(), s.description.c_str());
        if (!s.why.empty()) std::printf("%-20s why its settings: %s\n", "", s.why.c_str());
    }
    return 0;
}


int record(const Options& o) {
    const std::optional<frame::CheckpointInfo> resumed = resumed_run(o);
    const scene::Scene scene = resumed ? resumed->scene : load_scene(o);
    const std::uint64_t first = resumed ? resumed->frame : 0;
    const glm::ivec2 size = image_size(o, scene);
    const int frames = o.frames.value_or(120);
    const std::filesystem::path out = o.out.empty() ? std::filesystem::path("out") / scene.name : std::filesystem::path(o.out);
    if (resumed) check_resumed_folder(out, *resumed);
    frame::Progress progress = make_progress(o, "ranryu record");
    if (o.export_mesh && !render::needs_surface(shading(o).value_or(render::default_shading(scene))))
        throw InputError("--export-mesh: needs a surface (--shading water, fresnel, phong or gouraud of an SPH scene); scene " +
                         scene.name + " is drawn as particles");
    const shader::FileSource shaders = shader_source(o);   // a bad --shader-dir, before the folder is made
    if (o.no_png && o.video.empty() && o.export_particles.empty() && !o.export_mesh)
        throw InputError("--no-png: nothing would be recorded; add --video, --export-particles or --export-mesh");
    std::optional<record::ParticleFormat> particle_format;
    if (!o.export_particles.empty()) particle_format = record::parse_particle_format(o.export_particles, "--export-particles");
    // Check the video (its type, ffmpeg, an earlier file), the scene's memory and the folder before
    // any GPU work, so bad input costs nothing and loses nothing: nothing is created before the checks
    // have passed (the pipeline checks the memory again, as for every command).
    std::optional<record::VideoPlan> video;
    if (!o.video.empty()) video = record::VideoPlan::check(o.video, o.force);
    frame::View view{size.x, size.y, shading(o), true, record::Recorder::bytes_for(size.x, size.y)};
    if (o.export_mesh) view.extra_bytes += record::MeshExporter::bytes_for(std::size_t(scene.surface.max_vertices));
    auto ctx = headless(o, /*announce=*/false);
    frame::check_memory(scene, view, frame::device_memory());
    // The pipeline writes no file: built, and loaded from the checkpoint (which may yet be refused),
    // before the output is touched.
    frame::Pipeline pipeline(scene, shaders, view);
    if (resumed) frame::load_checkpoint(pipeline, o.resume, "--resume " + o.resume);
    if (video) video->prepare();
    const std::optional<std::uint64_t> resumed_at = resumed ? std::optional<std::uint64_t>(first) : std::nullopt;
    if (const std::size_t removed = record::prepare_output(out, o.force, resumed_at))
        std::printf("ranryu: --force: removed %zu files of an earlier run in %s\n", removed, out.string().c_str());
    print_device(ctx->info());
    SimulationLog log(pipeline, 0, o.records);
    if (resumed) log.resume_at(first, resumed->time);
    // A frame is written only once it is known sound (Pipeline::poll): an SPH frame once the guard's
    // record of it has arrived and is sound, every frame once it has ended without a GPU fault. A
    // capture can reach its writer before its frame ends (its readback may finish at once), so the
    // ballistic model is gated too, by the frames that ended.
    const bool gated = true;
    std::unique_ptr<record::Recorder> recorder;     // PNGs and the video (null with --no-png and no --video)
    std::unique_ptr<record::MeshExporter> meshes;   // --export-mesh: frame_NNNNN.ply, gated the same way
    std::unique_ptr<record::ParticleExporter> particles;   // --export-particles: particles_NNNNN.EXT, likewise
    auto validate = [&] {
        if (const auto sound = pipeline.poll()) {
            if (recorder) recorder->validate_through(*sound);
            if (meshes) meshes->validate_through(*sound);
            if (particles) particles->validate_through(*sound);
        }
        if (const auto& bad = pipeline.instability()) {
            if (recorder) recorder->discard_from(bad->frame);
            if (meshes) meshes->discard_from(bad->frame);
            if (particles) particles->discard_from(bad->frame);
        }
    };
    if (!o.no_png || video) {
        record::FrameSinks sinks{!o.no_png, nullptr};
        if (video) sinks.video = std::make_unique<record::VideoEncoder>(*video, size.x, size.y, scene.frame_dt);
        recorder = std::make_unique<record::Recorder>(pipeline.timer(), out, size.x, size.y, gated, validate, 3, 0,
                                                      std::move(sinks));
    }
    if (o.export_mesh)
        meshes = std::make_unique<record::MeshExporter>(pipeline.timer(), out, pipeline.mesh()->max_vertices(), gated, validate);
    if (particle_format)
        particles = std::make_unique<record::ParticleExporter>(pipeline.timer(), out, *particle_format, pipeline.particle_count(),
                                                               record::particle_buffers(pipeline), gated, validate);
    if (recorder) recorder->start_at(first);
    if (meshes) meshes->start_at(first);
    if (particles) particles->start_at(first);
    frame::FrameHooks hooks;
    hooks.after_draw = [&](frame::Pipeline& p) {
        if (recorder) recorder->capture(p.target());
        if (meshes) meshes->capture(p.mesh()->vertices(), p.mesh()->state());
        if (particles) particles->capture(record::particle_buffers(p));
    };
    hooks.after = [&](frame::Pipeline& p) {
        validate();
        progress.update(p);
    };
    progress.expect(first + std::uint64_t(frames));   // the progress line counts frames from the run's start
    log.start_clock();
    // A GPU fault (gl/faults.h: a GL error in a pass, a lost context, a fence that never signals)
    // stops the run like an instability: the frames before it are written, the faulting frame and
    // those after it are not, run.json says why, and the exit code is 1.
    std::optional<gl::GpuFault> fault;
    std::uint64_t ran = 0;
    try {
        ran = frame::run_frames(pipeline, std::uint64_t(frames), hooks);
    } catch (const gl::GpuFault& e) {
        fault = e;
        ran = pipeline.frames() - first;   // this run's frames (the fault's is pipeline.frames())
    }
    const bool interrupted = !fault && ran < std::uint64_t(frames) && frame::stop_requested();   // cut short by a signal
    progress.finish();
    // Stopped or not, every frame captured is written (or, after an instability, dropped) first; the
    // checkpoint before them, once the records have drained, so that a writer's failure (or ffmpeg
    // killed with the run by a batch system) cannot lose it.
    std::string checkpoint_error;
    auto finish = [&] {
        if (fault) {
            if (recorder) recorder->discard_from(first + ran);
            if (meshes) meshes->discard_from(first + ran);
            if (particles) particles->discard_from(first + ran);
        }
        pipeline.drain();
        validate();
        if (!fault) checkpoint_error = write_checkpoint(o, pipeline);
        if (recorder) recorder->finish();   // and closes the video: ffmpeg finishes the file
        if (meshes) meshes->finish();
        if (particles) particles->finish();
    };
    if (!fault) {
        finish();
    } else {
        try {
            finish();
        } catch (const gl::GpuFault&) {
            // The GPU is gone too far to drain (a lost context, a fence that never signals): what was
            // written stays, and run.json still says what happened.
        }
    }
    log.stop_clock();

    const profile::Report report = profile::summarize(pipeline.timer(), run_info(ctx->info(), pipeline, int(ran), 0), log.summary());
    nlohmann::json run = profile::to_json(report);
    if (resumed)
        run["resumed_from"] = {{"checkpoint", o.resume}, {"frame", resumed->frame}, {"time", resumed->time}};
    if (!o.checkpoint.empty())
        run["checkpoint"] = checkpoint_error.empty() && !fault
                                ? nlohmann::json({{"file", o.checkpoint}, {"frame", pipeline.frames()}, {"time", pipeline.simulated_time()}})
                                : nlohmann::json({{"file", nullptr}, {"not_written", fault ? "a GPU fault" : checkpoint_error}});
    run["scene_origin"] = scene.origin;
    run["frames_requested"] = frames;
    // A run stopped by SIGINT or SIGTERM: the frames before `interrupted_at_frame` ran.
    run["interrupted"] = interrupted;
    run["interrupted_at_frame"] = interrupted ? nlohmann::json(pipeline.frames()) : nlohmann::json(nullptr);
    run["fault"] = fault ? nlohmann::json({{"frame", first + ran}, {"message", fault->what()}}) : nlohmann::json(nullptr);
    const std::uint64_t pngs = recorder && !o.no_png ? recorder->frames_written() : 0;
    run["frames_written"] = pngs;
    run["frame_pattern"] = o.no_png ? nlohmann::json(nullptr) : nlohmann::json("frame_%05d.png");
    if (video)
        run["video"] = {{"file", video->file.string()}, {"codec", video->codec()}, {"frame_rate", record::frame_rate(scene.frame_dt)},
                        {"frames", recorder->video()->frames_written()}};
    if (particles)
        // In the GPU's order: each frame's neighbour-sort (cell) order, not the scene's (record/particle_files.h).
        run["particle_files"] = {{"format", o.export_particles},
                                 {"pattern", std::string("particles_%05d.") + record::extension(*particle_format)},
                                 {"count", pipeline.particle_count()},
                                 {"fields", particles->fields()},
                                 {"order", "gpu-cell-order"},
                                 {"frames_written", particles->frames_written()}};
    run["simulated_seconds"] = pipeline.simulated_time();
    run["shading"] = render::shading_name(pipeline.shading());
    run["device_memory"] = memory_json(pipeline.memory());
    if (meshes) {
        // Per written mesh: the MeshState's vertex count (every one is in the PLY) and its flags.
        nlohmann::json list = nlohmann::json::array();
        for (const record::MeshRecord& m : meshes->written())
            list.push_back({{"frame", m.frame}, {"vertices", m.vertices}, {"vertices_cut", m.cut}, {"grid_too_big", m.grid_too_big}});
        run["mesh_pattern"] = "frame_%05d.ply";
        run["meshes"] = list;
    }
    const std::string spikes = guard_spikes_line(pipeline, run);
    if (const auto& bad = pipeline.instability())
        run["instability"] = {{"frame", bad->frame}, {"step", bad->step}, {"time", bad->time},
                              {"criterion", bad->criterion}, {"particle", bad->particle},
                              {"value", bad->value}, {"limit", bad->limit}};
    const std::string report_name = resumed ? record::resumed_report_name(first) : std::string("run.json");
    profile::write_text_file(out / report_name, run.dump(2) + "\n", report_name + " in --out " + out.string());
    log.write_records(o.records);
    std::printf("wrote %llu frames (%dx%d) and %s to %s\n", static_cast<unsigned long long>(pngs), size.x, size.y,
                report_name.c_str(), out.string().c_str());
    if (video)
        std::printf("wrote the video %s (%llu frames, %s, %s fps)\n", video->file.string().c_str(),
                    static_cast<unsigned long long>(recorder->video()->frames_written()), video->codec(),
                    record::frame_rate(scene.frame_dt).c_str());
    if (particles)
        std::printf("wrote the particles of %llu frames as particles_*.%s\n",
                    static_cast<unsigned long long>(particles->frames_written()), record::extension(*particle_format));
    std::printf("%s", profile::table(report).c_str());
    std::printf("%s", spikes.c_str());
    if (fault) throw *fault;
    if (const auto& bad = pipeline.instability()) throw sim::UnstableError(*bad);
    if (!checkpoint_error.empty()) throw InputError(checkpoint_error);
    if (interrupted) throw frame::interrupted(ran, std::uint64_t(frames));
    return 0;
}

int profile_cmd(const Options& o) {
    const std::optional<frame::CheckpointInfo> resumed = resumed_run(o);
    const scene::Scene scene = resumed ? resumed->scene : load_scene(o);
    const glm::ivec2 size = image_size(o, scene);
    const int frames = o.frames.value_or(300);
    frame::Progress progress = make_progress(o, "ranryu profile");
    // The progress line counts frames from the run's start, a resumed run's from its checkpoint's.
    progress.expect((resumed ? resumed->frame : 0) + std::uint64_t(o.warmup) + std::uint64_t(frames));
    const shader::FileSource shaders = shader_source(o);
#ifndef RANRYU_HAVE_IMGUI
    if (o.overlay) throw InputError("--overlay: this build has no Dear ImGui (it was not found at configure time)");
#endif
    auto ctx = headless(o);
    frame::Pipeline pipeline(scene, shaders, size.x, size.y, shading(o));
    pipeline.timer().set_detail(o.detail);
    if (resumed) frame::load_checkpoint(pipeline, o.resume, "--resume " + o.resume);
    const std::uint64_t first = resumed ? resumed->frame : 0;
    SimulationLog log(pipeline, first + std::uint64_t(o.warmup), o.records);
    if (resumed) log.resume_at(first + std::uint64_t(o.warmup), resumed->time);
    // --overlay: the window's panel drawn into the offscreen target after each frame's picture, as
    // the pass "overlay" (GPU) and timed on the CPU (building the panel and recording its draws).
    frame::FrameHooks hooks = progress.hooks();
    std::vector<double> overlay_cpu_ms;
#ifdef RANRYU_HAVE_IMGUI
    std::unique_ptr<Overlay> overlay;
    OverlayState overlay_state;
    std::vector<input::Command> ignored;
    if (o.overlay) {
        overlay = std::make_unique<Overlay>(glm::ivec2(size.x, size.y), shaders);
        overlay_cpu_ms.reserve(std::size_t(frames));
        ignored.reserve(64);
        if (pipeline.simulation()) overlay_state.limits = sim::guard_limits(scene);
        overlay_state.viscosity = scene.sph.viscosity, overlay_state.cfl = scene.sph.courant();
        const profile::PassId pass = pipeline.timer().pass("overlay");
        hooks.after_draw = [&, pass](frame::Pipeline& p) {
            const auto t0 = std::chrono::steady_clock::now();
            glBindFramebuffer(GL_FRAMEBUFFER, p.target().framebuffer());
            glViewport(0, 0, size.x, size.y);
            overlay->draw(p, pass, overlay_state, ignored);
            glBindFramebuffer(GL_FRAMEBUFFER, 0);
            ignored.clear();
            if (overlay_cpu_ms.size() < overlay_cpu_ms.capacity())
                overlay_cpu_ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
        };
    }
#endif
    // Stopped by an instability or cut short by a signal: the records so far, and no report (a
    // signal's stop writes the checkpoint first).
    auto check_stopped = [&](bool cut_short) {
        const auto& bad = pipeline.instability();
        if (!bad && !cut_short) return;
        progress.finish();
        const std::string why = bad ? std::string() : write_checkpoint(o, pipeline);
        log.write_records(o.records);
        if (bad) throw sim::UnstableError(*bad);
        if (!why.empty()) throw InputError(why);
        throw frame::interrupted(pipeline.frames() - first, std::uint64_t(o.warmup) + std::uint64_t(frames));
    };
    bool cut_short = frame::run_frames(pipeline, std::uint64_t(o.warmup), hooks) < std::uint64_t(o.warmup) &&
                     frame::stop_requested();
    pipeline.drain();
    check_stopped(cut_short);
    pipeline.timer().reset_samples();
    overlay_cpu_ms.clear();
    if (turbulence::Subparticles* sub = pipeline.subparticles()) sub->count_from(pipeline.frames());
    log.start_clock();
    cut_short = frame::run_frames(pipeline, std::uint64_t(frames), hooks) < std::uint64_t(frames) &&
                frame::stop_requested();
    progress.finish();
    pipeline.drain();
    log.stop_clock();
    pipeline.poll();
    check_stopped(cut_short);
    const std::string checkpoint_error = write_checkpoint(o, pipeline);   // first; reported after the report
    log.write_records(o.records);

    const profile::Report report = profile::summarize(pipeline.timer(), run_info(ctx->info(), pipeline, frames, o.warmup), log.summary());
    std::printf("%s", profile::table(report).c_str());
    std::printf("%s", memory_line(pipeline.memory()).c_str());
    nlohmann::json extra = profile::to_json(report);
    std::printf("%s", guard_spikes_line(pipeline, extra).c_str());
    // What the scene does not run, and why (issue 12: a scene models no more than it needs).
    nlohmann::json skipped = nlohmann::json::array();
    for (const frame::SkippedStage& st : pipeline.skipped_stages()) {
        const std::string passes = st.text();
        std::printf("not run: %s, since %s\n", passes.c_str(), st.why.c_str());
        skipped.push_back({{"passes", passes}, {"names", st.passes}, {"why", st.why}});
    }
    extra["not_run"] = skipped;
    // The scene's other passes that took no sample in the timed frames, so that every named pass is
    // accounted for: in the table, in a "not run" line, or here.
    const std::string untimed = pipeline.untimed_passes();
    if (!untimed.empty())
        std::printf("not timed: %s (none ran in the timed frames: they run at start-up, in the warm-up, or on an event this run did not have)\n",
                    untimed.c_str());
    extra["not_timed"] = untimed;
    // Why the scene's solver and step settings are its own (sph.why, docs/SCENES.md); said to hold
    // for the scene as shipped, so a run at another spacing or with another solver says so.
    if (scene.model == scene::Model::sph && !scene.sph.why.empty()) {
        const bool as_shipped = !o.spacing && o.solver.empty();
        std::printf("why its settings: %s%s\n", scene.sph.why.c_str(),
                    as_shipped ? "" : " (said of the scene as shipped; --spacing or --solver changed it for this run)");
        extra["settings_why"] = {{"why", scene.sph.why}, {"as_shipped", as_shipped}};
    }
    extra["device_memory"] = memory_json(pipeline.memory());
    if (o.overlay) {
        // Its GPU time is the pass "overlay" in the table; this is the CPU's side of it.
        double sum = 0.0, most = 0.0;
        for (const double ms : overlay_cpu_ms) sum += ms, most = std::max(most, ms);
        const double mean = overlay_cpu_ms.empty() ? 0.0 : sum / double(overlay_cpu_ms.size());
        std::printf("overlay: CPU %.3f ms a frame (mean of %zu frames, most %.3f ms); GPU: the pass \"overlay\" above\n", mean,
                    overlay_cpu_ms.size(), most);
        extra["overlay"] = {{"cpu_ms_mean", mean}, {"cpu_ms_max", most}, {"frames", overlay_cpu_ms.size()}};
    }
    if (const surface::MarchingCubes* mc = pipeline.mesh()) {
        // After the run, not in the frame path: the last frame's mesh size, read once.
        const gpu::MeshState m = mc->state().read<gpu::MeshState>(1)[0];
        std::printf("surface (last frame): %u triangles from %u active of %u cells%s\n", m.draw.x / 3, m.totals.x,
                    m.cell_dispatch.w, m.totals.z ? ", cut to the vertex capacity" : "");
        extra["surface"] = {{"triangles", m.draw.x / 3}, {"active_cells", m.totals.x}, {"cells", m.cell_dispatch.w},
                            {"cut_to_capacity", m.totals.z != 0}};
    }
    std::string csv = profile::to_csv(report);
    if (const turbulence::Subparticles* sub = pipeline.subparticles()) {
        // The budget's stats came back with the frames (drained above): whether levels were dropped.
        const turbulence::SubparticleStats& st = sub->stats();
        const std::string note = turbulence::budget_note(st);
        const gpu::SubparticleState last = st.last.value_or(gpu::SubparticleState{});
        std::printf("sub-particles (last frame): %u from %u split of %u particles (levels 1-3: %u, %u, %u), cap %u\n",
                    last.dispatch.w, last.offsets.w, unsigned(pipeline.particle_count()), last.counts.x, last.counts.y,
                    last.counts.z, last.limits.x);
        if (!note.empty()) std::printf("%s\n", note.c_str());
        extra["subparticles"] = {{"budget", st.budget},
                                 {"levels", sub->levels_max()},
                                 {"frames", st.frames},
                                 {"frames_levels_dropped", st.dropped_frames},
                                 {"lowest_cap", st.dropped_frames ? st.lowest_cap : sub->levels_max()},
                                 {"most", st.most},
                                 {"last", {{"subparticles", last.dispatch.w}, {"split", last.offsets.w},
                                           {"counts", {last.counts.x, last.counts.y, last.counts.z}},
                                           {"cap", last.limits.x}, {"finest", last.limits.y}, {"wanted", last.limits.z}}},
                                 {"note", note}};
        // CSV: one more column with the note, the same on every row as the run's other facts.
        std::string with_note;
        std::size_t row = 0;
        for (std::size_t begin = 0, end; begin < csv.size(); begin = end + 1, ++row) {
            end = std::min(csv.find('\n', begin), csv.size());
            with_note += csv.substr(begin, end - begin) + ',' + (row == 0 ? std::string("note") : "\"" + note + "\"") + '\n';
        }
        csv = with_note;
    }
    if (!o.json.empty()) profile::write_text_file(o.json, extra.dump(2) + "\n", "--json " + o.json);
    if (!o.csv.empty()) profile::write_text_file(o.csv, csv, "--csv " + o.csv);
    if (!checkpoint_error.empty()) throw InputError(checkpoint_error);
    return 0;
}

}  // namespace ranryu::app
