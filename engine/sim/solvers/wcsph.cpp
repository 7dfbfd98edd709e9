#include "sim/solvers/wcsph.h"

#include <algorithm>

namespace ranryu::sim {

Wcsph::Wcsph(const shader::FileSource& shaders, profile::GpuTimer& timer, Fluid& fluid)
    : timer_(timer),
      density_pass_(timer.pass("density")),
      forces_pass_(timer.pass("forces")),
      density_(shader::Program::compute(shaders, "sim/wcsph/compute_density.comp", fluid.neighbour_defines())),
      forces_(shader::Program::compute(shaders, "sim/wcsph/compute_forces.comp", fluid.neighbour_defines())),
      pair_terms_(bytes_for(fluid.count()), GL_DYNAMIC_COPY, nullptr, "wcsph.pair_terms") {}

std::size_t Wcsph::bytes_for(std::size_t count) { return std::max<std::size_t>(count, 1) * sizeof(glm::vec2); }

void Wcsph::step(Fluid& fluid, StepHooks& hooks) {
    fluid.choose_time_step();
    fluid.rebuild_grid();
    compute_density(fluid);
    hooks.after_density(fluid);
    compute_forces(fluid);
    hooks.add_accelerations(fluid);
    fluid.integrate();
}

void Wcsph::compute_density(Fluid& fluid) {
    auto pass = timer_.scope(density_pass_);
    density_.bind(fluid.bind_state().with("PairTerms", pair_terms_)).dispatch(fluid.count());
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    fluid.set_neighbour_masks_current(true);
}

void Wcsph::compute_forces(Fluid& fluid) {
    auto pass = timer_.scope(forces_pass_);
    forces_.bind(fluid.bind_state().with("PairTerms", pair_terms_)).dispatch(fluid.count());
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

}  // namespace ranryu::sim
