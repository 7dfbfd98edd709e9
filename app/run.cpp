// ranryu run: the scene in a window, with the overlay's panel (app/overlay.h), through the one frame
// loop's hooks (frame/loop.h).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <vector>

#include <glm/glm.hpp>

#include "commands.h"
#include "core/error.h"
#include "frame/loop.h"
#include "frame/pipeline.h"
#include "record/png.h"
#include "sim/fluid.h"
#include "sim/guard.h"
#include "simulation_log.h"
#ifdef RANRYU_HAVE_GLFW
#include "gl/window.h"
#include "overlay.h"
#endif

namespace ranryu::app {

#ifdef RANRYU_HAVE_GLFW
namespace {

namespace fs = std::filesystem;

// Reads the window's back buffer (what the next swap shows) and writes it as a PNG. It waits for the
// GPU: only when a screenshot is asked for.
void save_back_buffer(const fs::path& file, glm::ivec2 fb) {
    std::vector<std::uint8_t> pixels(std::size_t(fb.x) * std::size_t(fb.y) * 4), flipped(pixels.size());
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    glReadBuffer(GL_BACK);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, fb.x, fb.y, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
    const std::size_t row = std::size_t(fb.x) * 4;
    for (int y = 0; y < fb.y; ++y)
        std::copy_n(pixels.data() + std::size_t(fb.y - 1 - y) * row, row, flipped.data() + std::size_t(y) * row);
    record::write_png(file, fb.x, fb.y, flipped.data());
}

}  // namespace
#endif

int run(const Options& o) {
#ifndef RANRYU_HAVE_GLFW
    (void)o;
    throw Error("this build has no window (GLFW was not found at configure time); use `ranryu record` or `ranryu profile`");
#else
    using Clock = std::chrono::steady_clock;
    const scene::Scene scene = load_scene(o);
    const glm::ivec2 size = image_size(o, scene);
    const std::uint64_t frames = std::uint64_t(o.frames.value_or(0));
    if (!o.screenshot.empty()) {
        // Refuse before opening anything: an existing file is earlier output, and the folder must exist.
        const fs::path shot(o.screenshot);
        if (fs::exists(shot)) throw InputError("--screenshot " + o.screenshot + ": the file exists; not overwriting it");
        const auto parent = shot.parent_path().empty() ? fs::path(".") : shot.parent_path();
        if (!fs::is_directory(parent)) throw InputError("--screenshot " + o.screenshot + ": no such folder");
    }
    const shader::FileSource shaders = shader_source(o);
    const bool debug = debug_context(o);
    gl::Window window(size.x, size.y, "ranryu - " + scene.name, debug);
    if (debug) gl::install_debug_callback();
    print_device(window.info());
    Overlay overlay(window.handle());
    frame::Pipeline pipeline(scene, shaders, size.x, size.y, shading(o));
    SimulationLog log(pipeline, 0);
    const profile::PassId present = pipeline.timer().pass("present");
    const profile::PassId overlay_pass = pipeline.timer().pass("overlay");
    OverlayState view;
    if (pipeline.simulation()) view.limits = sim::guard_limits(scene);
    // fps and the real-time factor over the last half second.
    Clock::time_point since = Clock::now();
    std::uint64_t frames_since = 0;
    double sim_since = 0.0;

    // Orbit camera: spherical coordinates around the scene's target.
    render::Camera cam = pipeline.camera();
    glm::vec3 arm = cam.eye - cam.target;
    float radius = glm::length(arm);
    float yaw = std::atan2(arm.x, arm.z), pitch = std::asin(glm::clamp(arm.y / radius, -1.0f, 1.0f));

    frame::FrameHooks hooks;
    hooks.keep_going = [&](const frame::Pipeline&) { return !window.should_close(); };
    hooks.before = [&](frame::Pipeline& p) {
        window.poll();
        const gl::Window::Input in = window.take_input();
        if (!overlay.wants_mouse() && (in.drag != glm::vec2(0.0f) || in.wheel != 0.0f)) {
            yaw -= 0.005f * in.drag.x;
            pitch = glm::clamp(pitch + 0.005f * in.drag.y, -1.5f, 1.5f);
            radius *= std::pow(0.9f, in.wheel);
            cam.eye = cam.target + radius * glm::vec3(std::cos(pitch) * std::sin(yaw), std::sin(pitch),
                                                      std::cos(pitch) * std::cos(yaw));
            p.set_camera(cam);
        }
    };
    hooks.after_draw = [&](frame::Pipeline& p) {
        const glm::ivec2 fb = window.framebuffer_size();
        {
            auto pass = p.timer().scope(present);
            glBindFramebuffer(GL_READ_FRAMEBUFFER, p.target().framebuffer());
            glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
            glBlitFramebuffer(0, 0, size.x, size.y, 0, 0, fb.x, fb.y, GL_COLOR_BUFFER_BIT, GL_LINEAR);
            glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
        }
        overlay.draw(p, overlay_pass, view);
        if (frames != 0 && p.frames() + 1 == frames && !o.screenshot.empty() && !p.instability()) {
            // Once, at exit: what the swap shows.
            save_back_buffer(o.screenshot, fb);
            std::printf("wrote %s (%dx%d)\n", o.screenshot.c_str(), fb.x, fb.y);
        }
    };
    hooks.after = [&](frame::Pipeline& p) {
        window.swap();
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
