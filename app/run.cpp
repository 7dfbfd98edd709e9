// ranryu run: the scene in a window, with the overlay's panel and the controls (app/overlay.h,
// input/commands.h), driven by a person or by --script (input/script.h). It runs the one frame loop
// (frame/loop.h) through its hooks; a restart (reset, another scene, shading or solver) ends the loop,
// rebuilds the pipeline and runs the loop again, keeping the window, the panel and the camera.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "commands.h"
#include "core/error.h"
#include "frame/loop.h"
#include "frame/pipeline.h"
#include "input/script.h"
#include "record/particle_files.h"
#include "record/recorder.h"
#include "sim/boundary.h"
#include "sim/fluid.h"
#include "sim/guard.h"
#include "simulation_log.h"
#include "turbulence/force.h"
#ifdef RANRYU_HAVE_GLFW
#include "gl/faults.h"
#include "gl/window.h"
#include "overlay.h"
#include "window_shots.h"
#endif

namespace ranryu::app {

#ifdef RANRYU_HAVE_GLFW
namespace {

namespace fs = std::filesystem;

// The screenshot folder: shot_00000.png, shot_00001.png, ...; an existing file is never replaced.
class Shots {
public:
    explicit Shots(fs::path dir) : dir_(std::move(dir)) {
        if (fs::exists(dir_) && !fs::is_directory(dir_)) throw InputError("--shots " + dir_.string() + ": not a folder");
    }
    fs::path next() {
        fs::create_directories(dir_);
        char name[32];
        for (;; ++counter_) {
            std::snprintf(name, sizeof name, "shot_%05d.png", counter_);
            // Past the name handed out, too: its file is written later, off the render thread.
            if (!fs::exists(dir_ / name)) {
                ++counter_;
                return dir_ / name;
            }
        }
    }

private:
    fs::path dir_;
    int counter_ = 0;
};

// The camera on a sphere around the scene's target: a drag turns it, the wheel moves it closer.
struct Orbit {
    render::Camera cam;
    float radius = 1.0f, yaw = 0.0f, pitch = 0.0f;
    explicit Orbit(const render::Camera& c = {}) : cam(c) {
        const glm::vec3 arm = cam.eye - cam.target;
        radius = glm::length(arm);
        yaw = std::atan2(arm.x, arm.z);
        pitch = radius > 0.0f ? std::asin(glm::clamp(arm.y / radius, -1.0f, 1.0f)) : 0.0f;
    }
    void move(glm::vec2 drag, float wheel) {
        yaw -= 0.005f * drag.x;
        pitch = glm::clamp(pitch + 0.005f * drag.y, -1.5f, 1.5f);
        radius *= std::pow(0.9f, wheel);
        cam.eye = cam.target + radius * glm::vec3(std::cos(pitch) * std::sin(yaw), std::sin(pitch), std::cos(pitch) * std::cos(yaw));
    }
};

// The recordings folder: each F9 (or `panel record on`) starts a take in the first take_NNN that
// does not exist yet, so a take never writes over an earlier one.
fs::path next_take(const fs::path& dir) {
    if (fs::exists(dir) && !fs::is_directory(dir)) throw InputError("--record-dir " + dir.string() + ": not a folder");
    char name[32];
    for (int k = 0;; ++k) {
        std::snprintf(name, sizeof name, "take_%03d", k);
        if (!fs::exists(dir / name)) return dir / name;
    }
}

// A drag of `pixels` on a picture `height` pixels high, as a displacement in the plane through
// `at` that faces the camera: at that depth one pixel spans 2 d tan(fov/2) / height metres.
glm::vec3 camera_plane_drag(const render::Camera& cam, glm::vec3 at, glm::vec2 pixels, int height) {
    const glm::vec3 forward = glm::normalize(cam.target - cam.eye);
    const glm::vec3 right = glm::normalize(glm::cross(forward, glm::vec3(0.0f, 1.0f, 0.0f)));
    const glm::vec3 up = glm::cross(right, forward);
    const float depth = std::max(glm::dot(at - cam.eye, forward), 1e-3f);
    const float metres = 2.0f * depth * std::tan(glm::radians(cam.fov_deg) * 0.5f) / float(std::max(height, 1));
    return metres * (pixels.x * right - pixels.y * up);
}

// Where the paddle may go: inside the tank, a radius and a spacing off every wall and the floor
// (up to a radius above an open top); an axis too narrow for that keeps its middle.
struct PaddleRange {
    glm::vec3 lo, hi;
    explicit PaddleRange(const scene::Scene& s) {
        const float r = s.paddle_radius, gap = r + s.spacing;
        lo = s.tank_min + gap;
        hi = s.tank_max - gap;
        if (!s.tank_closed) hi.y = s.tank_max.y + r;
        for (int a = 0; a < 3; ++a)
            if (lo[a] > hi[a]) lo[a] = hi[a] = 0.5f * (s.tank_min[a] + s.tank_max[a]);
    }
    glm::vec3 clamp(glm::vec3 p) const { return glm::clamp(p, lo, hi); }
    // Where it appears: over the middle of the tank, a spacing above the liquid's highest block.
    glm::vec3 spawn(const scene::Scene& s) const {
        const glm::vec3 c = 0.5f * (s.tank_min + s.tank_max);
        return clamp(glm::vec3(c.x, s.tank_min.y + s.fluid_height() + s.paddle_radius + s.spacing, c.z));
    }
};

int bundled_index(const std::string& name) {
    const std::vector<scene::BundledScene> all = scene::bundled();
    for (std::size_t i = 0; i < all.size(); ++i)
        if (all[i].name == name) return int(i);
    return -1;
}

}  // namespace
#endif

int run(const Options& o) {
#ifndef RANRYU_HAVE_GLFW
    (void)o;
    throw Error("this build has no window (GLFW was not found at configure time); use `ranryu record` or `ranryu profile`");
#else
    using Clock = std::chrono::steady_clock;
    scene::Scene scene = load_scene(o);
    const glm::ivec2 size = image_size(o, scene);
    const std::uint64_t frames = std::uint64_t(o.frames.value_or(0));
    // Refuse bad input before opening anything.
    // A file written at exit: an existing one is earlier output, and its folder must exist and be
    // writable (it is written as FILE.tmp, then renamed).
    auto check_new_file = [](const std::string& path, const std::string& option) {
        if (path.empty()) return;
        const std::string what = option + " " + path;
        profile::check_writable(path, what);   // a folder, a missing folder, no write access
        if (fs::exists(path)) throw InputError(what + ": the file exists; not overwriting it");
    };
    check_new_file(o.screenshot, "--screenshot");
    Shots shots(o.shots);
    if (fs::exists(o.record_dir) && !fs::is_directory(o.record_dir))
        throw InputError("--record-dir " + o.record_dir + ": not a folder");
    check_new_file(o.save_particles, "--save-particles");
    input::Replay script;
    if (!o.script.empty()) script = input::Replay(input::load_script(o.script));

    const shader::FileSource shaders = shader_source(o);
    const bool debug = debug_context(o);
    gl::Window window(size.x, size.y, "ranryu - " + scene.name, debug);
    if (debug) gl::install_debug_callback();
    gl::set_error_checks(debug);   // glGetError after every pass (gl/faults.h)
    print_device(window.info());
    Overlay overlay(window.handle(), shaders);
    WindowShots window_shots;   // --screenshot and the screenshot key, read back asynchronously

    // The controls' state, changed only by apply() (keys, panel widgets, script), read by the hooks.
    struct Controls {
        bool paused = false, step = false, panel = true, quit = false, restart = false, camera_moved = false;
        bool camera_from_scene = true;   // a new scene: its own camera
        int shots = 0;                   // screenshots asked for, one a frame
        std::optional<render::Shading> shading;
        bool turbulence = false;     // the force on (with scene.turbulence.amplitude) or off (A = 0)
        float amplitude = 5.0f;      // A for turning it on in a scene without it (a restart)
        bool settings_changed = true;   // viscosity, CFL or turbulence: into the pipeline before the next frame
        bool paddle = false;                 // the paddle is in the liquid (off at every start)
        glm::vec3 paddle_goal{0.0f};         // where the drags so far take it (it follows: sim::Simulation::set_paddle)
        bool record = false;                 // F9: the frames go to a take of --record-dir
        bool emitter = false;                // E: pouring liquid in, up to the budget (off at every start)
    } c;
    c.shading = shading(o);
    c.turbulence = scene.turbulence.enabled();
    OverlayState view;
    view.scene_index = scene.origin == "bundled" ? bundled_index(scene.name) : -1;
    Orbit orbit;
    std::vector<input::Command> pending;   // keys and panel widgets, applied before the next frame
    pending.reserve(64);
    auto queue = [&](const input::Command& cmd) {
        if (pending.size() < pending.capacity()) pending.push_back(cmd);
    };

    auto apply = [&](const input::Command& cmd) {
        const bool sph = scene.model == scene::Model::sph;
        switch (cmd.kind) {
            case input::Kind::toggle_pause: c.paused = !c.paused; break;
            case input::Kind::set_pause: c.paused = cmd.on; break;
            case input::Kind::step: c.paused = c.step = true; break;
            case input::Kind::reset: c.restart = true; break;
            case input::Kind::toggle_panel: c.panel = !c.panel; break;
            case input::Kind::set_panel: c.panel = cmd.on; break;
            case input::Kind::screenshot: ++c.shots; break;
            case input::Kind::quit: c.quit = true; break;
            case input::Kind::next_shading:
            case input::Kind::shading: {
                if (!sph) {
                    view.status = "scene " + scene.name + " uses the ballistic model: it is drawn as particles only";
                    break;
                }
                render::Shading s = cmd.shading;
                if (cmd.kind == input::Kind::next_shading) {
                    constexpr render::Shading order[] = {render::Shading::water, render::Shading::fresnel, render::Shading::phong,
                                                         render::Shading::gouraud, render::Shading::particles};
                    const render::Shading now = c.shading.value_or(render::default_shading(scene));
                    std::size_t i = 0;
                    while (order[i] != now) ++i;
                    s = order[(i + 1) % std::size(order)];
                }
                c.shading = s;
                c.restart = true;
                break;
            }
            case input::Kind::scene: {
                try {
                    scene::Scene next = scene::load(scene::bundled().at(std::size_t(cmd.index)).name);
                    Options only = o;   // --spacing for every scene, --solver where there is one
                    if (next.model != scene::Model::sph) only.solver.clear();
                    scene = with_options(std::move(next), only);
                } catch (const InputError& e) {
                    view.status = e.what();
                    break;
                }
                if (scene.model != scene::Model::sph) c.shading.reset();
                c.turbulence = scene.turbulence.enabled();
                c.settings_changed = true;
                view.scene_index = cmd.index;
                view.status.clear();
                c.camera_from_scene = c.restart = true;
                break;
            }
            case input::Kind::solver:
                if (!sph) {
                    view.status = "scene " + scene.name + " uses the ballistic model, which has no pressure solver";
                    break;
                }
                scene.sph.solver = cmd.solver;
                c.restart = true;
                break;
            case input::Kind::viscosity:
            case input::Kind::cfl:
            case input::Kind::amplitude:
            case input::Kind::turbulence:
            case input::Kind::toggle_turbulence: {
                if (!sph) {
                    view.status = "scene " + scene.name + " uses the ballistic model: no viscosity, time step or turbulence";
                    break;
                }
                // Kept in the scene, so that a restart keeps them too.
                if (cmd.kind == input::Kind::viscosity) scene.sph.viscosity = cmd.x;
                if (cmd.kind == input::Kind::cfl) scene.sph.courant() = cmd.x;
                if (cmd.kind == input::Kind::amplitude) {
                    c.amplitude = cmd.x;
                    if (scene.turbulence.enabled()) scene.turbulence.amplitude = cmd.x;
                }
                if (cmd.kind == input::Kind::turbulence || cmd.kind == input::Kind::toggle_turbulence) {
                    c.turbulence = cmd.kind == input::Kind::turbulence ? cmd.on : !c.turbulence;
                    // A scene without the force builds none of its passes: turning it on restarts it.
                    if (c.turbulence && !scene.turbulence.enabled()) {
                        scene.turbulence.amplitude = c.amplitude;
                        c.restart = true;
                    }
                }
                c.settings_changed = true;
                break;
            }
            case input::Kind::toggle_paddle:
            case input::Kind::set_paddle: {
                if (!sph) {
                    view.status = "scene " + scene.name + " uses the ballistic model: no paddle";
                    break;
                }
                const bool on = cmd.kind == input::Kind::set_paddle ? cmd.on : !c.paddle;
                if (on && !c.paddle) c.paddle_goal = PaddleRange(scene).spawn(scene);
                c.paddle = on;
                break;
            }
            case input::Kind::paddle_drag:
                if (c.paddle)
                    c.paddle_goal = PaddleRange(scene).clamp(c.paddle_goal + camera_plane_drag(orbit.cam, c.paddle_goal,
                                                                                               glm::vec2(cmd.x, cmd.y), size.y));
                break;
            case input::Kind::toggle_emitter:
            case input::Kind::set_emitter:
                if (!sph) {
                    view.status = "scene " + scene.name + " uses the ballistic model: no emitter";
                    break;
                }
                c.emitter = cmd.kind == input::Kind::set_emitter ? cmd.on : !c.emitter;
                break;
            case input::Kind::toggle_record:
            case input::Kind::set_record:
                c.record = cmd.kind == input::Kind::set_record ? cmd.on : !c.record;
                break;
            case input::Kind::spacing:
                try {
                    scene = scene::with_spacing(scene, cmd.x, "panel spacing");
                } catch (const InputError& e) {
                    view.status = e.what();
                    break;
                }
                view.status.clear();
                c.restart = true;
                break;
            case input::Kind::drag:
            case input::Kind::wheel:
                orbit.move(cmd.kind == input::Kind::drag ? glm::vec2(cmd.x, cmd.y) : glm::vec2(0.0f),
                           cmd.kind == input::Kind::wheel ? cmd.x : 0.0f);
                c.camera_moved = true;
                break;
        }
    };

    std::uint64_t base = 0;   // frames run by the pipelines before this one
    std::unique_ptr<record::Recorder> recorder;   // F9's take, while recording
    fs::path take;
    std::uint64_t take_from = 0;   // the pipeline's frame that is the take's frame_00000
    auto stop_recording = [&] {
        if (!recorder) return;
        recorder->finish();
        std::printf("recorded %llu frames into %s\n", static_cast<unsigned long long>(recorder->frames_written()), take.string().c_str());
        std::fflush(stdout);
        recorder.reset();
    };
    for (bool first = true;; first = false) {
        // Every SPH scene the window runs has a paddle, parked until it is switched on.
        scene.paddle_radius = scene.model == scene::Model::sph ? sim::paddle_radius_for(scene) : 0.0f;
        // And an emitter with a budget: --budget, or twice the scene's particles; all allocated now.
        scene.particle_budget = 0;
        if (scene.model == scene::Model::sph)
            scene.particle_budget = std::max<std::size_t>(o.budget ? std::size_t(*o.budget) : 2 * scene.particle_count(), scene.particle_count());
        c.paddle = c.emitter = false;
        frame::Pipeline pipeline(scene, shaders, size.x, size.y, c.shading);
        if (!first)
            std::printf("restart at frame %llu: %s, %s, %s\n", static_cast<unsigned long long>(base), scene.name.c_str(),
                        pipeline.simulation() ? scene::solver_name(scene.sph.solver) : "ballistic",
                        render::shading_name(pipeline.shading()));
        std::printf("particles: %zu at spacing %g m\n", scene.particle_count(), double(scene.spacing));
        if (scene.particle_budget) std::printf("particle budget: %zu (the emitter pours up to that)\n", scene.particle_budget);
        std::fflush(stdout);
        view.paddle_radius = scene.paddle_radius;
        if (c.camera_from_scene) orbit = Orbit(pipeline.camera());
        else pipeline.set_camera(orbit.cam);
        c.camera_from_scene = c.restart = c.camera_moved = false;
        c.step = c.paused;   // a restart shows its first frame, paused or not
        c.settings_changed = true;
        SimulationLog log(pipeline, 0);
        const profile::PassId present = pipeline.timer().pass("present");
        const profile::PassId overlay_pass = pipeline.timer().pass("overlay");
        view.limits.reset();
        if (pipeline.simulation()) view.limits = sim::guard_limits(scene);
        // fps and the real-time factor over the last half second.
        Clock::time_point since = Clock::now();
        std::uint64_t frames_since = 0;
        double sim_since = pipeline.simulated_time();
        view.rtf.reset();

        frame::FrameHooks hooks;
        // Before each frame: the window's input, the panel's widgets and the script's events due.
        hooks.keep_going = [&](const frame::Pipeline& p) {
            window.poll();
            const gl::Window::Keys keys = window.take_keys();
            for (std::size_t i = 0; i < keys.count && !overlay.wants_text(); ++i)
                if (const auto cmd = input::key_command(keys.names[i])) queue(*cmd);
            const gl::Window::Input in = window.take_input();
            if (!overlay.wants_mouse()) {
                if (in.drag != glm::vec2(0.0f)) queue({.kind = input::Kind::drag, .x = in.drag.x, .y = in.drag.y});
                if (in.wheel != 0.0f) queue({.kind = input::Kind::wheel, .x = in.wheel});
                if (in.right_drag != glm::vec2(0.0f)) queue({.kind = input::Kind::paddle_drag, .x = in.right_drag.x, .y = in.right_drag.y});
            }
            for (const input::Command& cmd : pending) apply(cmd);
            pending.clear();
            for (const std::uint64_t now = base + p.frames(); const input::Event* e = script.next_due(now); script.pop())
                apply(e->command);
            return !c.quit && !c.restart && !window.should_close();
        };
        // The sound frames so far into the take (Pipeline::poll): an SPH frame is written once the guard
        // has seen its record, every frame once it has ended without a GPU fault (a capture can reach its
        // writer before its frame ends), as `record` gates them (app/commands.cpp).
        auto validate_take = [&] {
            if (!recorder) return;
            if (const auto sound = pipeline.poll(); sound && *sound >= take_from) recorder->validate_through(*sound - take_from);
        };
        hooks.before = [&](frame::Pipeline& p) {
            if (std::exchange(c.camera_moved, false)) p.set_camera(orbit.cam);
            if (c.record && !recorder) {
                take = next_take(o.record_dir);
                fs::create_directories(take);
                take_from = p.frames();
                recorder = std::make_unique<record::Recorder>(p.timer(), take, size.x, size.y, /*gated=*/true, validate_take);
                std::printf("recording into %s\n", take.string().c_str());
                std::fflush(stdout);
            } else if (!c.record && recorder) {
                validate_take();
                stop_recording();
            }
            if (p.has_paddle()) p.simulation()->set_paddle(c.paddle, c.paddle_goal);
            if (p.simulation()) p.simulation()->set_emitter(c.emitter);
            view.emitter = c.emitter, view.budget = scene.particle_budget;
            view.paddle = c.paddle, view.recording = recorder != nullptr;
            if (std::exchange(c.settings_changed, false) && p.simulation()) {
                p.simulation()->fluid().set_viscosity_and_cfl(scene.sph.viscosity, scene.sph.courant());
                if (turbulence::TurbulenceForce* force = p.simulation()->turbulence())
                    force->set_amplitude(c.turbulence ? scene.turbulence.amplitude : 0.0f);
            }
            view.viscosity = scene.sph.viscosity, view.cfl = scene.sph.courant(), view.turbulence = c.turbulence;
            view.amplitude = scene.turbulence.enabled() ? scene.turbulence.amplitude : c.amplitude;
        };
        hooks.advance = [&](const frame::Pipeline&) { return !c.paused || std::exchange(c.step, false); };
        hooks.after_draw = [&](frame::Pipeline& p) {
            const glm::ivec2 fb = window.framebuffer_size();
            {
                auto pass = p.timer().scope(present);
                glBindFramebuffer(GL_READ_FRAMEBUFFER, p.target().framebuffer());
                glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
                glBlitFramebuffer(0, 0, size.x, size.y, 0, 0, fb.x, fb.y, GL_COLOR_BUFFER_BIT, GL_LINEAR);
                glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
            }
            view.paused = c.paused;
            if (recorder) recorder->capture(p.target());
            if (c.panel) overlay.draw(p, overlay_pass, view, pending);
            const std::uint64_t frame = base + p.frames();
            if (c.shots > 0) {
                --c.shots;
                const fs::path file = shots.next();
                const PanelRect& r = overlay.panel();
                char line[512];
                if (c.panel)
                    std::snprintf(line, sizeof line, "wrote %s (%dx%d, frame %llu, panel at %d,%d size %dx%d)", file.string().c_str(),
                                  fb.x, fb.y, static_cast<unsigned long long>(frame), r.x, r.y, r.width, r.height);
                else
                    std::snprintf(line, sizeof line, "wrote %s (%dx%d, frame %llu, no panel)", file.string().c_str(), fb.x, fb.y,
                                  static_cast<unsigned long long>(frame));
                window_shots.take(file, fb, line);
            }
            if (frames != 0 && frame + 1 == frames && !o.screenshot.empty() && !p.instability())
                window_shots.take(o.screenshot, fb, "wrote " + o.screenshot + " (" + std::to_string(fb.x) + "x" + std::to_string(fb.y) + ")");
        };
        hooks.after = [&](frame::Pipeline& p) {
            validate_take();
            window.swap();
            window_shots.poll();
            ++frames_since;
            const Clock::time_point now = Clock::now();
            if (const double dt = std::chrono::duration<double>(now - since).count(); dt >= 0.5) {
                const double sim_now = p.simulated_time();
                view.fps = double(frames_since) / dt;
                view.rtf = (sim_now - sim_since) / dt;
                since = now, frames_since = 0, sim_since = sim_now;
            }
        };

        log.start_clock();
        base += frame::run_frames(pipeline, frames ? std::optional<std::uint64_t>(frames - base) : std::nullopt, hooks);
        // Every record and timing still on its way (the guard's last word included), and the shots.
        pipeline.drain();
        window_shots.finish();
        log.stop_clock();
        pipeline.poll();
        if (recorder) {
            // A take ends with its pipeline; after an instability, without the frames that show it.
            if (const auto& bad = pipeline.instability(); bad && bad->frame >= take_from) recorder->discard_from(bad->frame - take_from);
            validate_take();
            stop_recording();
        }
        if (const auto& bad = pipeline.instability()) throw sim::UnstableError(*bad);
        if (c.restart && !c.quit && !window.should_close() && !(frames && base >= frames)) continue;
        if (!o.save_particles.empty()) {
            // After the run, not in the frame path: the last frame's particles, read once.
            std::vector<glm::vec4> x = pipeline.positions().read<glm::vec4>(pipeline.particle_count());
            std::vector<glm::vec4> v = pipeline.velocities().read<glm::vec4>(pipeline.particle_count());
            std::vector<char> scratch;
            const std::string ext = fs::path(o.save_particles).extension().string();
            record::write_particles(ext == ".vtp" ? record::ParticleFormat::vtp : record::ParticleFormat::ply, o.save_particles,
                                    record::ParticleFrame{x, v, {}, {}, {}}, scratch);
            std::printf("wrote %s (%zu particles)\n", o.save_particles.c_str(), x.size());
        }
        if (const auto active = pipeline.active_particles(); active && scene.particle_budget)
            std::printf("particles: %zu active of budget %zu\n", *active, scene.particle_budget);
        if (const sim::Simulation* sim = pipeline.simulation(); sim && sim->paddle_on()) {
            const glm::vec3 at = sim->paddle_center();
            std::printf("paddle at %.6f %.6f %.6f radius %.6f m\n", double(at.x), double(at.y), double(at.z),
                        double(sim->paddle_scale() * scene.paddle_radius));
        }
        const profile::Report report =
            profile::summarize(pipeline.timer(), run_info(window.info(), pipeline, int(pipeline.frames()), 0), log.summary());
        std::printf("%s", profile::table(report).c_str());
        return 0;
    }
#endif
}

}  // namespace ranryu::app
