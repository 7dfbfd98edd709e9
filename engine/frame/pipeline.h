#pragma once
// One frame of ranryu as a list of GPU passes (frame/loop.h runs them for every command):
//
//     pipeline.begin_frame();
//     pipeline.simulate();        // ballistic: "ballistic.integrate" x substeps; SPH: sim/simulation.h, then, with
//                                 // sub-particles (turbulence/subparticles.h) "subparticles.classify",
//                                 // ".scan", ".compact", ".budget", ".spawn"; then, when the
//                                 // shading draws a surface, ("surface.anisotropy"), "surface.bounds",
//                                 // ("subparticles.splat"), ("level-set.splat"), "level-set" and
//                                 // "mc.classify", "mc.compact", "mc.emit"
//                                 // (surface/level_set.h, surface/marching_cubes.h) mesh the liquid
//     pipeline.draw();            // "clear", "draw-floor", "draw-tank", "draw-particles" (with the
//                                 // sub-particles, coloured by level) or "draw-surface"; the water
//                                 // shading: "shadow-map", ("clear", "draw-sky", "draw-floor",
//                                 // "draw-walls", "draw-tank": in frames whose view changed),
//                                 // "liquid-thickness", "compose", "draw-surface"; with
//                                 // sub-particles, "draw-spray"
//                                 // after the surface, and with the paddle on (run), "draw-paddle"
//                                 // (render/renderer.h)
//     recorder.capture(...);      // "readback"   (record only)
//     pipeline.end_frame();
//
// Nothing here reads the GPU back or waits for it: per-pass timings and the SPH guard's records come
// back through rings, frames late. poll() collects them; a record that breaks a guard criterion makes
// instability() non-empty and the frame loop stops.
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "frame/memory.h"
#include "gl/objects.h"
#include "profile/gpu_timer.h"
#include "render/renderer.h"
#include "scene/scene.h"
#include "shader/source.h"
#include "sim/guard.h"
#include "sim/particles.h"
#include "sim/simulation.h"
#include "surface/level_set.h"
#include "surface/marching_cubes.h"
#include "turbulence/subparticles.h"

namespace ranryu::frame {

// What a pipeline draws: a width x height target in a shading mode (default:
// render::default_shading(scene)), or nothing (draw = false: validation runs simulate only, and build
// no renderer, surface or target).
struct View {
    int width = 960, height = 540;
    std::optional<render::Shading> shading;
    bool draw = true;
    // Device memory the command allocates beside the pipeline (record's readback rings), counted
    // in the memory check (frame/memory.h).
    std::size_t extra_bytes = 0;
};

// A stage of the frame that a scene or view leaves out, with why: a scene models no more than it
// needs, and `profile` says what it did not run (the passes named as the timer names them).
struct SkippedStage {
    std::vector<std::string> passes;   // the timer's names, or a prefix and '*' ("mc.*"): {"wavelet", "turbulence-force"}
    std::string whose;                 // what the names are, when they alone mislead ("WCSPH's"); may be empty
    std::string why;                   // e.g. "turbulence.amplitude is 0"
    // "wavelet, turbulence-force", and ": " + whose when there is one.
    std::string text() const;
    // Whether `pass` is one of passes, or starts with a prefix of one.
    bool names(std::string_view pass) const;
};

class Pipeline {
public:
    // Builds every program (start-up) and allocates the particle state and the view's target. A
    // shading other than particles also builds the level set and marching cubes (scene.surface); a
    // scene that draws particles builds neither. Throws InputError for a surface shading of a
    // ballistic scene (it has no neighbour grid to mesh from), and, before allocating anything, for
    // a scene whose memory_estimate() the device has no room for (frame/memory.h).
    Pipeline(const scene::Scene& scene, const shader::FileSource& shaders, const View& view);
    Pipeline(const scene::Scene& scene, const shader::FileSource& shaders, int width, int height,
             std::optional<render::Shading> shading = std::nullopt)
        : Pipeline(scene, shaders, View{width, height, shading, true}) {}
    // The device memory a pipeline of `scene` drawn as `view` allocates, by component: what the
    // constructor builds, from each component's bytes_for() (frame/memory.h). Needs the context the
    // pipeline will run in current: the particles' raster depends on its renderer
    // (render::ImpostorOptions::from_environment()).
    static MemoryEstimate memory_estimate(const scene::Scene& scene, const View& view);
    // The passes hold references to the pipeline's timer: a pipeline stays where it was built.
    Pipeline(const Pipeline&) = delete;
    Pipeline& operator=(const Pipeline&) = delete;

    void begin_frame() { timer_.begin_frame(); }
    void simulate();   // advances scene.frame_dt of simulated time
    void draw();       // nothing when the view does not draw
    bool draws() const { return renderer_ != nullptr; }
    void end_frame();

    // Collects the guard's records (and the sub-particles' stats) that have arrived. Returns the last frame known to be sound
    // (every frame for the ballistic model, which has no guard), or nothing yet.
    std::optional<std::uint64_t> poll();
    const std::optional<sim::Instability>& instability() const;
    // End of a run: waits for the outstanding records (not the frame path).
    void drain();

    // The paddle (scene.paddle_radius > 0): sim::Simulation::set_paddle(); drawn as the pass
    // "draw-paddle" while it is on.
    bool has_paddle() const { return sph_ && sph_->fluid().has_paddle(); }
    // The particles not parked as of the last record (the emitter pours parked ones in: sim/fluid.h),
    // or nothing yet; particle_count() is the budget, all allocated.
    std::optional<std::size_t> active_particles() const;

    void set_camera(const render::Camera& cam);
    const render::Camera& camera() const { return camera_; }

    const scene::Scene& scene() const { return scene_; }
    // The memory estimate, the device's figure it was checked against and what was allocated.
    const MemoryUse& memory() const { return memory_; }
    profile::GpuTimer& timer() { return timer_; }
    std::vector<SkippedStage> skipped_stages() const;
    // The passes the timer knows (named by the scene's parts) that took no time sample since its last
    // reset and that skipped_stages() does not name: those that ran before (at start-up, in the
    // warm-up), or run only on an event (the emitter, a paddle, a view change) or a command (the noise
    // export) the run did not have; not a pass within another that ran untimed (the report's
    // untimed_within names those). Comma-separated, in the order they were named; empty when none.
    std::string untimed_passes() const;
    const gl::RenderTarget& target() const { return target_; }
    std::size_t particle_count() const;
    const gl::Buffer& positions() const;
    const gl::Buffer& velocities() const;
    // The SPH simulation (null for the ballistic model).
    sim::Simulation* simulation() { return sph_.get(); }
    const sim::Simulation* simulation() const { return sph_.get(); }
    render::Shading shading() const { return shading_; }
    // The surface's mesh (null when the shading draws particles): vertices() and state() as
    // MarchingCubes documents them, written by this frame's simulate().
    const surface::MarchingCubes* mesh() const { return mc_.get(); }
    // The sub-particles (null unless scene.turbulence.subparticles.enabled(): then nothing of them
    // is built and no pass of theirs runs), written by this frame's simulate().
    turbulence::Subparticles* subparticles() { return sub_.get(); }
    const turbulence::Subparticles* subparticles() const { return sub_.get(); }
    // Simulated time: the GPU's clock as last read back for SPH (frames late), else simulated frames x
    // frame_dt.
    double simulated_time() const;
    // Substeps a frame: for SPH those of the frame whose record came back last (nothing before the
    // first), else the scene's fixed count.
    std::optional<std::uint32_t> substeps_per_frame() const;
    std::uint64_t frames() const { return frames_; }
    // Checkpoints (frame/checkpoint.h): the frame count and the simulation's state (sim/state_io.h).
    // What a frame draws or meshes is made again from that state by the next frame.
    void persist(sim::StateIo& io);
    // The frame this pipeline began at: 0, or the checkpoint's it was loaded from.
    std::uint64_t first_frame() const { return first_frame_; }
    // Frames that simulated: frames() less those the frame loop held (FrameHooks::advance, run's pause).
    std::uint64_t simulated_frames() const { return simulated_frames_; }

private:
    scene::Scene scene_;
    profile::GpuTimer timer_;
    std::unique_ptr<sim::Particles> ballistic_;
    std::unique_ptr<sim::Simulation> sph_;
    std::unique_ptr<turbulence::Subparticles> sub_;
    std::unique_ptr<surface::LevelSet> level_set_;
    std::unique_ptr<surface::MarchingCubes> mc_;
    render::Shading shading_;
    std::unique_ptr<render::Renderer> renderer_;   // null when the view does not draw
    gl::RenderTarget target_;
    render::Camera camera_;
    int substeps_ = 1;
    std::uint64_t frames_ = 0;
    std::uint64_t simulated_frames_ = 0;
    std::uint64_t first_frame_ = 0;
    // Tests: RANRYU_FAULT_AT_FRAME=N makes frame N raise a GL error in a pass of its own
    // ("fault-injection"), so the fault path (gl/faults.h) runs end to end.
    std::optional<std::uint64_t> inject_fault_at_;
    std::optional<profile::PassId> fault_pass_;
    MemoryUse memory_;
    gl::Buffer paddle_sphere_;   // (center, radius), (velocity, 0): draw-paddle's instance
};

}  // namespace ranryu::frame
