#pragma once
// Weakly compressible SPH (docs/SPH.md): pressure from the Tait equation of state, explicit. A step:
//
//     "choose-time-step", "hash", "sort.*", "reorder"   (Fluid)
//     "density"           eqs. (2), (3), the flags and neighbour masks
//     (hooks.after_density)
//     "forces"            eqs. (4), (5) and gravity
//     (hooks.add_accelerations)
//     "integrate"         eq. (6), (8) and the guard's records (Fluid)
//
// Its time step is bound by the artificial sound speed c = 10·v_max (eq. (7)): the reference the
// incompressible solver is measured against, and the low end of the speed/accuracy chart.
#include "gl/objects.h"
#include "shader/program.h"
#include "sim/fluid.h"
#include "sim/solver.h"

namespace ranryu::sim {

class Wcsph final : public Solver {
public:
    Wcsph(const shader::FileSource& shaders, profile::GpuTimer& timer, Fluid& fluid);
    // Device memory the constructor allocates for `count` particles (frame/memory.h).
    static std::size_t bytes_for(std::size_t count);
    scene::Solver kind() const override { return scene::Solver::wcsph; }
    void step(Fluid& fluid, StepHooks& hooks) override;

    // A step's stages, public for tests that compare each with the CPU reference.
    void compute_density(Fluid& fluid);   // "density"
    void compute_forces(Fluid& fluid);    // "forces"

private:
    profile::GpuTimer& timer_;
    profile::PassId density_pass_, forces_pass_;
    shader::Program density_, forces_;
    gl::Buffer pair_terms_;   // vec2 per particle: (rho, p/rho^2), the forces pass's gathers
};

}  // namespace ranryu::sim
