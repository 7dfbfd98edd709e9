#pragma once
// Position Based Fluids (docs/PBF.md; Macklin & Müller 2013): the density constraint C_i = rho_i/rho0 − 1
// solved on the positions by Jacobi iterations, a fixed number of substeps a frame and of iterations a
// substep (sph.pbf), so a frame's cost is known before it runs. A step:
//
//     "choose-time-step"   (Fluid) dt = frame_dt / substeps: the fixed step (sph_params() sets no CFL)
//     "pbf.predict"        (P1): x* = x + dt (v + dt a), the step's start x_n kept in a carried array
//     "hash", "sort.*", "reorder"   (Fluid) on x*
//     iterations × [ "pbf.lambda"   (P2)-(P4), (P9): rho, lambda; the first also the flags and masks
//                    (hooks.after_density, hooks.add_accelerations after the first)
//                    "pbf.correct"  (P5), (P6): x += dx into the other buffer, then swapped ]
//     "pbf.velocity"       (P7): the projection of docs/SPH.md (8), v = (x − x_n)/dt
//     "pbf.viscosity"      (P7): XSPH; the guard's records unless vorticity confinement is on
//     "pbf.vorticity"      (P8), sph.pbf.vorticity > 0 only: the confinement, the guard's records
//
// The hooks' accelerations (the turbulence force) enter the next step's prediction (P1): a PBF step
// predicts before its neighbourhoods, and so before the density the hooks read.
#include "gl/objects.h"
#include "shader/program.h"
#include "shared/bindings.h"
#include "sim/fluid.h"
#include "sim/solver.h"

namespace ranryu::sim {

class Pbf final : public Solver {
public:
    Pbf(const shader::FileSource& shaders, profile::GpuTimer& timer, const scene::Scene& scene, Fluid& fluid);
    // Device memory the constructor allocates for `count` particles, its carried step start included
    // (frame/memory.h).
    static std::size_t bytes_for(const scene::Scene& scene, std::size_t count);
    // The PbfParams of a scene with particle spacing `spacing` (docs/PBF.md symbols).
    static gpu::PbfParams params_for(const scene::Scene& scene);
    scene::Solver kind() const override { return scene::Solver::pbf; }
    void step(Fluid& fluid, StepHooks& hooks) override;
    void persist(StateIo& io) override;

    // A step's stages, public for tests that compare each with the CPU reference; step() runs them in
    // this order, the hooks after the first compute_lambda().
    void predict(Fluid& fluid);                          // "pbf.predict"
    // "pbf.lambda"; `first`: the walk that records the masks; `last`: the iteration whose densities the
    // guard records.
    void compute_lambda(Fluid& fluid, bool first, bool last);
    void correct_positions(Fluid& fluid);                // "pbf.correct", then the swap
    void update_velocities(Fluid& fluid);                // "pbf.velocity"
    void apply_viscosity(Fluid& fluid);                  // "pbf.viscosity" and, when on, "pbf.vorticity"

    int iterations() const { return int(params_.iterations); }
    const gpu::PbfParams& params() const { return params_; }
    // Per-particle arrays in the fluid's current cell order (tests).
    const gl::Buffer& lambda() const { return lambda_; }          // float: lambda_i (P4) of the last lambda pass
    const gl::Buffer& start() const { return fluid_.carried(start_); }   // vec4: x_n (P1)
    const gl::Buffer& step_velocities() const { return velocity_; }      // vec4: (x − x_n)/dt (P7) before XSPH
    const gl::Buffer& vorticity() const { return vorticity_; }           // vec4: omega_i, |omega_i| (P8)
    const gl::Buffer& warm() const { return fluid_.carried(warm_); }     // vec4: (P10)'s carried term (warm_start > 0 only)
    gl::Buffer& warm() { return fluid_.carried(warm_); }
    gl::Buffer& mask_origins() { return mask_origins_; }   // vec4: x* of the boundary's masks (with them only)

private:
    shader::StorageSet state(Fluid& fluid) const;

    profile::GpuTimer& timer_;
    profile::PassId predict_pass_, lambda_pass_, correct_pass_, velocity_pass_, viscosity_pass_, vorticity_pass_;
    bool vorticity_on_;
    shader::Program predict_, lambda_walk_, lambda_program_, correct_, velocity_update_, viscosity_, vorticity_confine_;
    gpu::PbfParams params_{};
    gl::Buffer params_ubo_, lambda_, velocity_, vorticity_;
    gl::Buffer mask_origins_;   // vec4: x* where the first lambda pass recorded the boundary masks (pbf.glsl)
    Fluid& fluid_;
    int start_, warm_;
};

}  // namespace ranryu::sim
