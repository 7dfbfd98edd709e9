#include "commands.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <memory>

#include <glm/gtc/constants.hpp>

#include "core/error.h"
#include "frame/loop.h"
#include "frame/pipeline.h"
#include "frame/progress.h"
#include "frame/stop.h"
#include "gl/context.h"
#include "gl/faults.h"
#include "profile/report.h"
#include "record/mesh_export.h"
#include "record/png.h"
#include "record/recorder.h"
#include "scene/scene.h"
#include "shader/source.h"
#include "sim/guard.h"
#ifdef RANRYU_HAVE_GLFW
#include "gl/window.h"
#endif

namespace ranryu::app {
namespace {

#ifdef NDEBUG
constexpr bool kDebugBuild = false;
#else
constexpr bool kDebugBuild = true;
#endif

}  // namespace

shader::FileSource shader_source(const Options& o) {
    std::string dir = o.shader_dir;
    if (dir.empty())
        if (const char* env = std::getenv("RANRYU_SHADER_DIR")) dir = env;
    if (dir.empty()) return shader::FileSource::embedded();
    if (!std::filesystem::is_directory(dir)) throw InputError("--shader-dir " + dir + ": not a folder");
    return shader::FileSource::directory(dir);
}

namespace {

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
    info.substeps = p.scene().model == scene::Model::sph ? 0 : p.scene().substeps();
    info.frame_dt = p.scene().frame_dt;
    return info;
}

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

}  // namespace

void print_device(const gl::DeviceInfo& d) {
    std::printf("ranryu %s | %s\n", RANRYU_VERSION, d.line().c_str());
    if (!d.timer_queries) std::printf("ranryu: this context has no timer queries; timings will read 0\n");
    std::fflush(stdout);
}

// Headless context, with the debug callback in Debug builds or with --gl-debug.
std::unique_ptr<gl::HeadlessContext> headless(const Options& o, bool announce) {
    const bool debug = kDebugBuild || o.gl_debug;
    auto ctx = std::make_unique<gl::HeadlessContext>(debug);
    if (debug) gl::install_debug_callback();
    gl::set_error_checks(debug);   // glGetError after every pass (gl/faults.h)
    if (announce) print_device(ctx->info());
    return ctx;
}

scene::Scene load_scene(const Options& o) { return with_options(scene::load(o.scene), o); }

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

int scenes(const Options&) {
    for (const scene::BundledScene& s : scene::bundled()) std::printf("%-20s %s\n", s.name.c_str(), s.description.c_str());
    return 0;
}

namespace {

// The summary of what the simulation did from the frame `from` on, fed by the fluid's records, and
// (--records) every record as a CSV row.
class SimulationLog {
public:
    SimulationLog(frame::Pipeline& p, std::uint64_t from, const std::string& records = {}) : from_(from) {
        if (sim::Simulation* sim = p.simulation()) {
            summary_.emplace();
            summary_->solver = scene::solver_name(p.scene().sph.solver);
            if (!records.empty()) csv_ = profile::record_csv_header();
            sim->fluid().set_record_sink([this, keep = !records.empty()](const gpu::StepState& r) {
                if (r.frame >= from_) summary_->add(r);
                else summary_->start_time = r.time;
                if (keep) csv_ += profile::record_csv_row(r);
            });
        }
    }
    // Writes the rows (after the run: not the frame path).
    void write_records(const std::string& path) const {
        if (!path.empty()) profile::write_text_file(path, csv_, "--records " + path);
    }
    void start_clock() { start_ = std::chrono::steady_clock::now(); }
    void stop_clock() {
        if (summary_) summary_->wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    }
    const std::optional<profile::SimulationSummary>& summary() const { return summary_; }

private:
    std::uint64_t from_;
    std::optional<profile::SimulationSummary> summary_;
    std::string csv_;
    std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

}  // namespace

int record(const Options& o) {
    const scene::Scene scene = load_scene(o);
    const glm::ivec2 size = image_size(o, scene);
    const int frames = o.frames.value_or(120);
    const std::filesystem::path out = o.out.empty() ? std::filesystem::path("out") / scene.name : std::filesystem::path(o.out);
    frame::Progress progress = make_progress(o, "ranryu record");
    if (o.export_mesh && !render::needs_surface(shading(o).value_or(render::default_shading(scene))))
        throw InputError("--export-mesh: needs a surface (--shading phong, gouraud or fresnel of an SPH scene); scene " +
                         scene.name + " is drawn as particles");
    // The scene's memory and the folder are checked before anything is built or written, so bad input
    // costs little and loses nothing (the pipeline checks the memory again, as for every command).
    frame::View view{size.x, size.y, shading(o), true, record::Recorder::bytes_for(size.x, size.y)};
    if (o.export_mesh) view.extra_bytes += record::MeshExporter::bytes_for(std::size_t(scene.surface.max_vertices));
    const shader::FileSource shaders = shader_source(o);
    auto ctx = headless(o, /*announce=*/false);
    frame::check_memory(scene, view, frame::device_memory());
    if (const std::size_t removed = record::prepare_output(out, o.force))
        std::printf("ranryu: --force: removed %zu files of an earlier run in %s\n", removed, out.string().c_str());
    print_device(ctx->info());
    frame::Pipeline pipeline(scene, shaders, view);
    SimulationLog log(pipeline, 0, o.records);
    // SPH frames are written only once the guard's record of them has arrived and is sound.
    std::unique_ptr<record::Recorder> recorder;
    std::unique_ptr<record::MeshExporter> meshes;   // --export-mesh: frame_NNNNN.ply, gated the same way
    auto validate = [&] {
        if (const auto sound = pipeline.poll()) {
            recorder->validate_through(*sound);
            if (meshes) meshes->validate_through(*sound);
        }
        if (const auto& bad = pipeline.instability()) {
            recorder->discard_from(bad->frame);
            if (meshes) meshes->discard_from(bad->frame);
        }
    };
    recorder = std::make_unique<record::Recorder>(pipeline.timer(), out, size.x, size.y,
                                                  scene.model == scene::Model::sph, validate);
    if (o.export_mesh)
        meshes = std::make_unique<record::MeshExporter>(pipeline.timer(), out, pipeline.mesh()->max_vertices(),
                                                        scene.model == scene::Model::sph, validate);
    frame::FrameHooks hooks;
    hooks.after_draw = [&](frame::Pipeline& p) {
        recorder->capture(p.target());
        if (meshes) meshes->capture(p.mesh()->vertices(), p.mesh()->state());
    };
    hooks.after = [&](frame::Pipeline& p) {
        validate();
        progress.update(p);
    };
    progress.expect(std::uint64_t(frames));
    log.start_clock();
    const std::uint64_t ran = frame::run_frames(pipeline, std::uint64_t(frames), hooks);
    const bool interrupted = ran < std::uint64_t(frames) && frame::stop_requested();   // cut short by a signal
    progress.finish();
    // Stopped or not, every frame captured is written (or, after an instability, dropped) first.
    pipeline.drain();
    log.stop_clock();
    validate();
    recorder->finish();
    if (meshes) meshes->finish();

    const profile::Report report = profile::summarize(pipeline.timer(), run_info(ctx->info(), pipeline, int(ran), 0), log.summary());
    nlohmann::json run = profile::to_json(report);
    run["scene_origin"] = scene.origin;
    run["frames_requested"] = frames;
    // A run stopped by SIGINT or SIGTERM: the frames before `interrupted_at_frame` ran.
    run["interrupted"] = interrupted;
    run["interrupted_at_frame"] = interrupted ? nlohmann::json(ran) : nlohmann::json(nullptr);
    run["frames_written"] = recorder->frames_written();
    run["frame_pattern"] = "frame_%05d.png";
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
    if (const auto& bad = pipeline.instability())
        run["instability"] = {{"frame", bad->frame}, {"step", bad->step}, {"time", bad->time},
                              {"criterion", bad->criterion}, {"particle", bad->particle},
                              {"value", bad->value}, {"limit", bad->limit}};
    profile::write_text_file(out / "run.json", run.dump(2) + "\n", "run.json in --out " + out.string());
    log.write_records(o.records);
    std::printf("wrote %llu frames (%dx%d) and run.json to %s\n", static_cast<unsigned long long>(recorder->frames_written()),
                size.x, size.y, out.string().c_str());
    std::printf("%s", profile::table(report).c_str());
    if (const auto& bad = pipeline.instability()) throw sim::UnstableError(*bad);
    if (interrupted) throw frame::interrupted(ran, std::uint64_t(frames));
    return 0;
}

int profile_cmd(const Options& o) {
    const scene::Scene scene = load_scene(o);
    const glm::ivec2 size = image_size(o, scene);
    const int frames = o.frames.value_or(300);
    frame::Progress progress = make_progress(o, "ranryu profile");
    progress.expect(std::uint64_t(o.warmup) + std::uint64_t(frames));
    const shader::FileSource shaders = shader_source(o);
    auto ctx = headless(o);
    frame::Pipeline pipeline(scene, shaders, size.x, size.y, shading(o));
    SimulationLog log(pipeline, std::uint64_t(o.warmup), o.records);
    // Stopped by an instability or cut short by a signal: the records so far, and no report.
    auto check_stopped = [&](bool cut_short) {
        const auto& bad = pipeline.instability();
        if (!bad && !cut_short) return;
        progress.finish();
        log.write_records(o.records);
        if (bad) throw sim::UnstableError(*bad);
        throw frame::interrupted(pipeline.frames(), std::uint64_t(o.warmup) + std::uint64_t(frames));
    };
    bool cut_short = frame::run_frames(pipeline, std::uint64_t(o.warmup), progress.hooks()) < std::uint64_t(o.warmup) &&
                     frame::stop_requested();
    pipeline.drain();
    check_stopped(cut_short);
    pipeline.timer().reset_samples();
    if (turbulence::Subparticles* sub = pipeline.subparticles()) sub->count_from(pipeline.frames());
    log.start_clock();
    cut_short = frame::run_frames(pipeline, std::uint64_t(frames), progress.hooks()) < std::uint64_t(frames) &&
                frame::stop_requested();
    progress.finish();
    pipeline.drain();
    log.stop_clock();
    pipeline.poll();
    check_stopped(cut_short);
    log.write_records(o.records);

    const profile::Report report = profile::summarize(pipeline.timer(), run_info(ctx->info(), pipeline, frames, o.warmup), log.summary());
    std::printf("%s", profile::table(report).c_str());
    std::printf("%s", memory_line(pipeline.memory()).c_str());
    nlohmann::json extra = profile::to_json(report);
    extra["device_memory"] = memory_json(pipeline.memory());
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
    return 0;
}

int run(const Options& o) {
#ifndef RANRYU_HAVE_GLFW
    (void)o;
    throw Error("this build has no window (GLFW was not found at configure time); use `ranryu record` or `ranryu profile`");
#else
    const scene::Scene scene = load_scene(o);
    const glm::ivec2 size = image_size(o, scene);
    const int frames = o.frames.value_or(0);
    if (!o.screenshot.empty()) {
        // Refuse before opening anything: an existing file is earlier output, and the folder must exist.
        const std::filesystem::path shot(o.screenshot);
        if (std::filesystem::exists(shot)) throw InputError("--screenshot " + o.screenshot + ": the file exists; not overwriting it");
        const auto parent = shot.parent_path().empty() ? std::filesystem::path(".") : shot.parent_path();
        if (!std::filesystem::is_directory(parent)) throw InputError("--screenshot " + o.screenshot + ": no such folder");
    }
    const shader::FileSource shaders = shader_source(o);
    const bool debug = kDebugBuild || o.gl_debug;
    gl::Window window(size.x, size.y, "ranryu - " + scene.name, debug);
    if (debug) gl::install_debug_callback();
    gl::set_error_checks(debug);
    print_device(window.info());
    frame::Pipeline pipeline(scene, shaders, size.x, size.y, shading(o));
    SimulationLog log(pipeline, 0);
    const profile::PassId present = pipeline.timer().pass("present");

    // Orbit camera: spherical coordinates around the scene's target.
    render::Camera cam = pipeline.camera();
    glm::vec3 arm = cam.eye - cam.target;
    float radius = glm::length(arm);
    float yaw = std::atan2(arm.x, arm.z), pitch = std::asin(glm::clamp(arm.y / radius, -1.0f, 1.0f));

    frame::FrameHooks hooks;
    hooks.keep_going = [&](const frame::Pipeline&) { return !window.should_close(); };
    hooks.before = [&](frame::Pipeline& p) {
        window.poll();
        if (const gl::Window::Input in = window.take_input(); in.drag != glm::vec2(0.0f) || in.wheel != 0.0f) {
            yaw -= 0.005f * in.drag.x;
            pitch = glm::clamp(pitch + 0.005f * in.drag.y, -1.5f, 1.5f);
            radius *= std::pow(0.9f, in.wheel);
            cam.eye = cam.target + radius * glm::vec3(std::cos(pitch) * std::sin(yaw), std::sin(pitch),
                                                      std::cos(pitch) * std::cos(yaw));
            p.set_camera(cam);
        }
    };
    glm::ivec2 fb{0};
    hooks.after_draw = [&](frame::Pipeline& p) {
        fb = window.framebuffer_size();
        auto pass = p.timer().scope(present);
        glBindFramebuffer(GL_READ_FRAMEBUFFER, p.target().framebuffer());
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
        glBlitFramebuffer(0, 0, size.x, size.y, 0, 0, fb.x, fb.y, GL_COLOR_BUFFER_BIT, GL_LINEAR);
        glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    };
    hooks.after = [&](frame::Pipeline& p) {
        const bool last = frames != 0 && p.frames() == std::uint64_t(frames);
        if (last && !o.screenshot.empty() && !p.instability()) {
            // Once, at exit: read the window's back buffer, which is what the swap shows.
            std::vector<std::uint8_t> pixels(std::size_t(fb.x) * std::size_t(fb.y) * 4), flipped(pixels.size());
            glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
            glReadBuffer(GL_BACK);
            glPixelStorei(GL_PACK_ALIGNMENT, 1);
            glReadPixels(0, 0, fb.x, fb.y, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
            const std::size_t row = std::size_t(fb.x) * 4;
            for (int y = 0; y < fb.y; ++y)
                std::copy_n(pixels.data() + std::size_t(fb.y - 1 - y) * row, row, flipped.data() + std::size_t(y) * row);
            record::write_png(o.screenshot, fb.x, fb.y, flipped.data());
            std::printf("wrote %s (%dx%d)\n", o.screenshot.c_str(), fb.x, fb.y);
        }
        window.swap();
    };
    log.start_clock();
    frame::run_frames(pipeline, frames ? std::optional<std::uint64_t>(frames) : std::nullopt, hooks);
    pipeline.drain();
    log.stop_clock();
    if (const auto& bad = pipeline.instability()) throw sim::UnstableError(*bad);
    const profile::Report report =
        profile::summarize(pipeline.timer(), run_info(window.info(), pipeline, int(pipeline.frames()), 0), log.summary());
    std::printf("%s", profile::table(report).c_str());
    return 0;
#endif
}

}  // namespace ranryu::app
