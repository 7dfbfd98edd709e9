#pragma once
// One frame of ranryu as a list of GPU passes. The callers (app/commands) read as:
//
//     pipeline.begin_frame();
//     pipeline.simulate();        // ballistic: "integrate" x substeps; SPH: see sim/sph.h
//     pipeline.draw();            // "clear", "draw-floor", "draw-tank", "draw-particles"
//     recorder.capture(...);      // "readback"   (record only)
//     pipeline.end_frame();
//
// Nothing here reads the GPU back or waits for it: per-pass timings and the SPH guard's records come
// back through rings, frames late. poll() collects them; a record that breaks a guard criterion makes
// instability() non-empty and the caller stops.
#include <memory>
#include <optional>

#include "gl/objects.h"
#include "profile/gpu_timer.h"
#include "render/renderer.h"
#include "scene/scene.h"
#include "shader/source.h"
#include "sim/guard.h"
#include "sim/particles.h"
#include "sim/sph.h"

namespace ranryu::frame {

class Pipeline {
public:
    // Builds every program (start-up), allocates the particle state and a width x height target.
    Pipeline(const scene::Scene& scene, const shader::FileSource& shaders, int width, int height);

    void begin_frame() { timer_.begin_frame(); }
    void simulate();   // advances scene.frame_dt of simulated time
    void draw();
    void end_frame();

    // Collects the guard's records that have arrived. Returns the last frame known to be sound
    // (every frame for the ballistic model, which has no guard), or nothing yet.
    std::optional<std::uint64_t> poll();
    const std::optional<sim::Instability>& instability() const;
    // End of a run: waits for the outstanding records (not the frame path).
    void drain();

    void set_camera(const render::Camera& cam);
    const render::Camera& camera() const { return camera_; }

    const scene::Scene& scene() const { return scene_; }
    profile::GpuTimer& timer() { return timer_; }
    const gl::RenderTarget& target() const { return target_; }
    std::size_t particle_count() const;
    const gl::Buffer& positions() const;
    const gl::Buffer& velocities() const;
    sim::Sph* sph() { return sph_.get(); }
    // Simulated time: the GPU's clock as last read back for SPH (frames late), else frames x frame_dt.
    double simulated_time() const;
    std::uint64_t frames() const { return frames_; }

private:
    scene::Scene scene_;
    profile::GpuTimer timer_;
    std::unique_ptr<sim::Particles> ballistic_;
    std::unique_ptr<sim::Sph> sph_;
    render::Renderer renderer_;
    gl::RenderTarget target_;
    render::Camera camera_;
    int substeps_ = 1;
    std::uint64_t frames_ = 0;
};

}  // namespace ranryu::frame
