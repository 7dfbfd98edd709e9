#include "sim/solver.h"

#include "sim/fluid.h"
#include "sim/solvers/dfsph.h"
#include "sim/solvers/wcsph.h"

namespace ranryu::sim {

std::unique_ptr<Solver> make_solver(const shader::FileSource& shaders, profile::GpuTimer& timer,
                                    const scene::Scene& scene, Fluid& fluid) {
    switch (scene.sph.solver) {
        case scene::Solver::wcsph: return std::make_unique<Wcsph>(shaders, timer, fluid);
        case scene::Solver::dfsph: break;
    }
    return std::make_unique<Dfsph>(shaders, timer, scene, fluid);
}

}  // namespace ranryu::sim
