#include "sim/simulation.h"

#include "turbulence/force.h"

namespace ranryu::sim {

Simulation::Simulation(const shader::FileSource& shaders, profile::GpuTimer& timer, const scene::Scene& scene)
    : fluid_(shaders, timer, scene), solver_(make_solver(shaders, timer, scene, fluid_)) {
    if (scene.turbulence.enabled())
        turbulence_ = std::make_unique<turbulence::TurbulenceForce>(shaders, timer, scene.turbulence, fluid_);
}

Simulation::~Simulation() = default;

void Simulation::begin_frame(std::uint64_t frame) {
    fluid_.begin_frame(frame);
    solver_->begin_frame(fluid_);
}

void Simulation::step() {
    if (turbulence_) solver_->step(fluid_, *turbulence_);
    else solver_->step(fluid_, none_);
}

void Simulation::end_frame() { fluid_.end_frame(); }

void Simulation::advance(std::uint64_t frame) {
    begin_frame(frame);
    for (int s = 0; s < fluid_.substeps_this_frame(); ++s) step();
    end_frame();
}

}  // namespace ranryu::sim
