#pragma once
// Boundary particles (docs/SPH.md eq. (8)): the tank's floor and four walls (the top is open) and
// every obstacle, sampled on lattices of the fluid's spacing in `layers` layers on the solid side of
// each surface. Positions only (w = 0); the GPU computes each particle's psi_b at start.
#include <vector>

#include <glm/glm.hpp>

namespace ranryu::scene { struct Scene; }

namespace ranryu::sim {

// Enough layers that a fluid particle touching a surface has a full kernel of boundary behind it.
int boundary_layers(float spacing, float support);

std::vector<glm::vec4> sample_boundary(const scene::Scene& s, int layers);

}  // namespace ranryu::sim
