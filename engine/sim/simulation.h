#pragma once
// An SPH simulation: the fluid's state (sim/fluid.h), the solver that advances it (sim/solver.h) and
// the passes that act between the solver's stages (the turbulence force, turbulence/force.h, when the
// scene turns it on). One frame:
//
//     begin_frame(frame)        "begin-frame"; the fluid and the solver plan the frame (substeps,
//                               iteration caps) from the fluid's planning_record()
//     step() × substeps         the solver's step, with the turbulence as its hooks
//     end_frame()               "record-extremes": the frame's fastest and densest particles into its
//                               record; "diagnostics": the record is queued for readback
//
// advance() runs the three. Nothing here reads the GPU back; end_frame() waits only as the fluid's
// readback ring's back-pressure (sim/fluid.h end_frame()).
#include <cstdint>
#include <memory>

#include <glm/glm.hpp>

#include "profile/gpu_timer.h"
#include "scene/scene.h"
#include "shader/source.h"
#include "sim/fluid.h"
#include "sim/solver.h"

namespace ranryu::turbulence { class TurbulenceForce; }

namespace ranryu::sim {

class Simulation {
public:
    Simulation(const shader::FileSource& shaders, profile::GpuTimer& timer, const scene::Scene& scene);
    ~Simulation();

    void advance(std::uint64_t frame);   // one frame of scene.frame_dt
    void begin_frame(std::uint64_t frame);
    void step();
    void end_frame();
    int substeps_this_frame() const { return fluid_.substeps_this_frame(); }

    // The paddle (scene.paddle_radius > 0; sim/boundary.h): on, it appears at `goal` when it was off,
    // growing from nothing to its radius at the pace below (so that liquid there is pushed aside, not
    // crushed), and moves towards `goal` by at most
    // kPaddleStep spacings a substep and at most kPaddleSpeed times the scene's speed estimate
    // sqrt(2 g H) (the fluid it pushes moves as fast; the guard's bound is 5 times that), with the
    // velocity of that move, re-sorting the boundary before each substep it moves in
    // (Fluid::move_paddle); off, it is parked. Acts from the next step().
    static constexpr float kPaddleStep = 0.25f, kPaddleSpeed = 0.5f;
    void set_paddle(bool on, glm::vec3 goal) { paddle_on_ = on, paddle_goal_ = goal; }
    bool paddle_on() const { return paddle_placed_on_; }
    glm::vec3 paddle_center() const { return paddle_center_; }
    glm::vec3 paddle_velocity() const { return paddle_velocity_; }
    float paddle_scale() const { return paddle_scale_; }   // the part of its radius it has grown to

    // The emitter (scene.particle_budget above its count; sim/fluid.h): on, every frame pours a sheet
    // (pass "emit", at the frame's start) until the budget is spent; the GPU keeps the count.
    void set_emitter(bool on) { emitting_ = on; }
    bool emitting() const { return emitting_; }

    // Checkpoints (frame/checkpoint.h): the fluid's state and the solver's (sim/state_io.h). The
    // turbulence keeps nothing of its own from frame to frame (its noise seeds are the fluid's carried
    // arrays, its tiles come from the scene's seed).
    void persist(StateIo& io);

    Fluid& fluid() { return fluid_; }
    const Fluid& fluid() const { return fluid_; }
    Solver& solver() { return *solver_; }
    // The turbulence force, or null when the scene's turbulence is off (then nothing of it exists).
    turbulence::TurbulenceForce* turbulence() { return turbulence_.get(); }
    const turbulence::TurbulenceForce* turbulence() const { return turbulence_.get(); }

private:
    Fluid fluid_;
    std::unique_ptr<Solver> solver_;
    std::unique_ptr<turbulence::TurbulenceForce> turbulence_;
    StepHooks none_;
    float frame_dt_, paddle_speed_;
    bool paddle_on_ = false, paddle_placed_on_ = false, emitting_ = false;
    glm::vec3 paddle_goal_{0.0f}, paddle_center_{0.0f}, paddle_velocity_{0.0f};
    float paddle_scale_ = 0.0f;
    void place_paddle();
};

}  // namespace ranryu::sim
