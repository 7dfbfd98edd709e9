#pragma once
// A φ grid on the CPU: the same layout the GPU passes use (glsl/shared/bindings.h, "surface"):
// node (i, j, k) at origin + spacing·(i, j, k), value phi[i + nx·(j + ny·k)], φ > 0 inside.
// The input of the CPU references (surface::level_set_cpu fills one, surface::polygonise_cpu meshes one).
#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

namespace ranryu::surface {

struct PhiGrid {
    glm::vec3 origin{0.0f};
    float spacing = 1.0f;
    glm::uvec3 dims{0u};
    std::vector<float> phi;

    std::size_t nodes() const { return std::size_t(dims.x) * dims.y * dims.z; }
    std::size_t index(glm::uvec3 n) const { return n.x + std::size_t(dims.x) * (n.y + std::size_t(dims.y) * n.z); }
    // Computed as the GPU passes compute it: origin + spacing * vec3(n), in float.
    glm::vec3 node(glm::uvec3 n) const { return origin + spacing * glm::vec3(n); }
    float at(glm::uvec3 n) const { return phi[index(n)]; }
};

}  // namespace ranryu::surface
