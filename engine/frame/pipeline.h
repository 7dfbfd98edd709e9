#pragma once
// One frame of ranryu as a list of GPU passes. The callers (app/commands) read as:
//
//     pipeline.begin_frame();
//     pipeline.simulate();        // "integrate" × substeps
//     pipeline.draw();            // "clear", "draw-floor", "draw-tank", "draw-particles"
//     recorder.capture(...);      // "readback"   (record only)
//     pipeline.end_frame();
//
// Nothing here reads the GPU back or waits for it; per-pass timings come back through the
// GpuTimer's ring, frames late.
#include "gl/objects.h"
#include "profile/gpu_timer.h"
#include "render/renderer.h"
#include "scene/scene.h"
#include "shader/source.h"
#include "sim/particles.h"

namespace ranryu::frame {

class Pipeline {
public:
    // Builds every program (start-up), allocates the particle state and a width×height target.
    Pipeline(const scene::Scene& scene, const shader::FileSource& shaders, int width, int height);

    void begin_frame() { timer_.begin_frame(); }
    void simulate();   // advances scene.frame_dt of simulated time
    void draw();
    void end_frame();

    void set_camera(const render::Camera& cam);
    const render::Camera& camera() const { return camera_; }

    const scene::Scene& scene() const { return scene_; }
    profile::GpuTimer& timer() { return timer_; }
    const gl::RenderTarget& target() const { return target_; }
    const sim::Particles& particles() const { return particles_; }
    double simulated_time() const { return sim_time_; }
    std::uint64_t frames() const { return frames_; }

private:
    scene::Scene scene_;
    profile::GpuTimer timer_;
    sim::Particles particles_;
    render::Renderer renderer_;
    gl::RenderTarget target_;
    render::Camera camera_;
    int substeps_ = 1;
    double sim_time_ = 0.0;
    std::uint64_t frames_ = 0;
};

}  // namespace ranryu::frame
