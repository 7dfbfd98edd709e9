#pragma once
// A pressure solver (docs/METHOD.md §2): the algorithm that advances the fluid's state (sim/fluid.h)
// by one step. The solvers are siblings over one state, as in SPlisHSPlasH: WCSPH (docs/SPH.md) and
// DFSPH (docs/DFSPH.md) in sim/solvers/; the turbulence, the surface and the frame loop see only the
// state and this interface, so a solver is added without touching them. PBF (docs/PBF.md) is the
// third: it corrects positions instead of solving for a pressure, in the same slots of the step.
//
// A step is, for every solver:
//
//     fluid.choose_time_step()            the step's dt, on the GPU
//     fluid.rebuild_grid()                the state in cell order
//     the solver's density pass           rho, the flags and the neighbour masks of this order
//     hooks.after_density(fluid)          passes that read them (the wavelet analysis)
//     the non-pressure accelerations      into fluid.accelerations()
//     hooks.add_accelerations(fluid)      passes that add to them (the turbulence force)
//     the pressure and the integration    positions and velocities of the step's end
#include <cstddef>
#include <memory>
#include <string_view>

#include "profile/gpu_timer.h"
#include "scene/scene.h"
#include "shader/source.h"

namespace ranryu::sim {

class Fluid;
class StateIo;

// Passes that act on the fluid between a solver's stages.
class StepHooks {
public:
    virtual ~StepHooks() = default;
    virtual void after_density(Fluid&) {}       // densities, flags and masks are current
    virtual void add_accelerations(Fluid&) {}   // accelerations() holds the non-pressure ones; add to them
};

class Solver {
public:
    virtual ~Solver() = default;
    virtual scene::Solver kind() const = 0;
    // Once a frame, after fluid.begin_frame(): plans the frame from fluid.planning_record() (iteration caps).
    virtual void begin_frame(Fluid&) {}
    virtual void step(Fluid& fluid, StepHooks& hooks) = 0;
    // The solver's own state from step to step, and what it planned from the records (sim/state_io.h;
    // its per-particle warm starts are the fluid's carried arrays, saved with the fluid).
    virtual void persist(StateIo&) {}
    // When in a frame the pressure the solver leaves in Density.y after the frame is of, in frames
    // before the frame's end: 0 where it is the last step's (WCSPH, PBF), 0.5 where it is the frame's
    // Δt-weighted mean (DFSPH, docs/DFSPH.md "The pressure a frame"). Read by the validation cases that
    // sample it over time.
    virtual double pressure_sample_offset() const { return 0.0; }
};

// The scene's solver (scene.sph.solver), its programs built (start-up) and its arrays allocated for `fluid`.
std::unique_ptr<Solver> make_solver(const shader::FileSource& shaders, profile::GpuTimer& timer,
                                    const scene::Scene& scene, Fluid& fluid);
// Device memory the scene's solver allocates for `count` particles (frame/memory.h).
std::size_t solver_bytes(const scene::Scene& scene, std::size_t count);

}  // namespace ranryu::sim
