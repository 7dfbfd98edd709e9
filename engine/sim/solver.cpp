#include "sim/solver.h"

#include "sim/fluid.h"
#include "sim/solvers/dfsph.h"
#include "sim/solvers/pbf.h"
#include "sim/solvers/wcsph.h"

namespace ranryu::sim {

std::unique_ptr<Solver> make_solver(const shader::FileSource& shaders, profile::GpuTimer& timer,
                                    const scene::Scene& scene, Fluid& fluid) {
    switch (scene.sph.solver) {
        case scene::Solver::wcsph: return std::make_unique<Wcsph>(shaders, timer, fluid);
        case scene::Solver::pbf: return std::make_unique<Pbf>(shaders, timer, scene, fluid);
        case scene::Solver::dfsph: break;
    }
    return std::make_unique<Dfsph>(shaders, timer, scene, fluid);
}

std::size_t solver_bytes(const scene::Scene& scene, std::size_t count) {
    switch (scene.sph.solver) {
        case scene::Solver::wcsph: return Wcsph::bytes_for(count);
        case scene::Solver::pbf: return Pbf::bytes_for(scene, count);
        case scene::Solver::dfsph: break;
    }
    const std::size_t boundary = Fluid::boundary_count(scene);
    return Dfsph::bytes_for(count, boundary, scene.sph.boundary_rows, scene.sph.chebyshev > 0.0f, scene.sph.gradient_correction,
                           Fluid::neighbour_runs(scene), Dfsph::wall_gradient_stored(scene, boundary));
}

}  // namespace ranryu::sim
