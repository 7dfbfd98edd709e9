#pragma once
// An SPH simulation: the fluid's state (sim/fluid.h), the solver that advances it (sim/solver.h) and
// the passes that act between the solver's stages (the turbulence force, turbulence/force.h, when the
// scene turns it on). One frame:
//
//     begin_frame(frame)        "begin-frame"; the solver reads what has come back (iteration caps)
//     step() × substeps         the solver's step, with the turbulence as its hooks
//     end_frame()               "diagnostics": the frame's record is queued for readback
//
// advance() runs the three. Nothing here waits for the GPU.
#include <cstdint>
#include <memory>

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
};

}  // namespace ranryu::sim
