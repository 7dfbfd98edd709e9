#pragma once
// φ grids for marching-cubes tests: random fields that exercise every cube case, ambiguous faces
// included, and that are negative on the border so the surface is closed.
#include <cmath>

#include <glm/glm.hpp>

#include "support/gl_fixture.h"   // ranryu::test::Random
#include "surface/phi_grid.h"

namespace ranryu::test {

// Each node gets ±m with m in [0.1, 1] and a fair coin for the sign; border nodes are negative. At least
// one inner node is inside, so there is a surface to check: a 4x4x4 grid has 8 inner nodes, all outside
// with probability 1/256 (seed 2938675188 drew it: no triangle, zero volume). Needs dims >= 3 on each axis.
inline surface::PhiGrid random_closed_field(Random& rng, glm::vec3 origin, float spacing, glm::uvec3 dims) {
    surface::PhiGrid g{origin, spacing, dims, {}};
    g.phi.resize(g.nodes());
    bool inside = false;
    for (std::uint32_t k = 0; k < dims.z; ++k)
        for (std::uint32_t j = 0; j < dims.y; ++j)
            for (std::uint32_t i = 0; i < dims.x; ++i) {
                const bool border = i == 0 || j == 0 || k == 0 || i + 1 == dims.x || j + 1 == dims.y || k + 1 == dims.z;
                const float m = rng.uniform(0.1f, 1.0f);
                const bool in = !border && rng.below(2) == 0;
                g.phi[g.index({i, j, k})] = in ? m : -m;
                inside = inside || in;
            }
    if (!inside) g.phi[g.index(dims / 2u)] = -g.phi[g.index(dims / 2u)];   // an inner node (dims >= 3)
    return g;
}

// φ = R - |x - c| on a grid of spacing h, kept 1e-3 h off zero: a crossing closer to a node than a
// float's resolution of the position lands on the node, where the weld (by exact position) would
// merge distinct edge vertices into one and the mesh would read as non-manifold (CI failed on seeds
// 2431792292 and 218461786 before).
inline surface::PhiGrid sphere(glm::vec3 origin, float h, glm::uvec3 dims, glm::vec3 centre, float R) {
    surface::PhiGrid g{origin, h, dims, {}};
    g.phi.resize(g.nodes());
    for (std::uint32_t k = 0; k < dims.z; ++k)
        for (std::uint32_t j = 0; j < dims.y; ++j)
            for (std::uint32_t i = 0; i < dims.x; ++i) {
                const float f = R - float(glm::length(glm::dvec3(g.node({i, j, k})) - glm::dvec3(centre)));
                g.phi[g.index({i, j, k})] = std::abs(f) < 1e-3f * h ? std::copysign(1e-3f * h, f) : f;
            }
    return g;
}

}  // namespace ranryu::test
