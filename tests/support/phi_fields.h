#pragma once
// φ grids for marching-cubes tests: random fields that exercise every cube case, ambiguous faces
// included, and that are negative on the border so the surface is closed.
#include <glm/glm.hpp>

#include "support/gl_fixture.h"   // ranryu::test::Random
#include "surface/phi_grid.h"

namespace ranryu::test {

// Each node gets ±m with m in [0.1, 1] and a fair coin for the sign; border nodes are negative.
inline surface::PhiGrid random_closed_field(Random& rng, glm::vec3 origin, float spacing, glm::uvec3 dims) {
    surface::PhiGrid g{origin, spacing, dims, {}};
    g.phi.resize(g.nodes());
    for (std::uint32_t k = 0; k < dims.z; ++k)
        for (std::uint32_t j = 0; j < dims.y; ++j)
            for (std::uint32_t i = 0; i < dims.x; ++i) {
                const bool border = i == 0 || j == 0 || k == 0 || i + 1 == dims.x || j + 1 == dims.y || k + 1 == dims.z;
                const float m = rng.uniform(0.1f, 1.0f);
                g.phi[g.index({i, j, k})] = border || rng.below(2) ? -m : m;
            }
    return g;
}

}  // namespace ranryu::test
