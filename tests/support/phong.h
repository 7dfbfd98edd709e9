#pragma once
// The CPU reference of glsl/common/frame.glsl's shade_phong, for the raster tests: Phong of one
// directional light, display-encoded (clamp, gamma 2.2), in 0..255:
//     c = L·(k_a·base + k_d·max(n·l, 0)·base + k_s·max(r·v, 0)^s),  r = reflect(−l, n),
// specular 0 where n·l ≤ 0; k_a = light_color.a, (k_d, k_s, s) = material.xyz.
#include <algorithm>
#include <cmath>

#include <glm/glm.hpp>

#include "shared/bindings.h"

namespace ranryu::test {

inline glm::dvec3 phong(const gpu::FrameParams& f, glm::dvec3 base, glm::dvec3 n, glm::dvec3 v) {
    const glm::dvec3 l(f.light_dir);
    const double ndl = glm::dot(n, l);
    const double spec = ndl > 0.0 ? std::pow(std::max(glm::dot(glm::reflect(-l, n), v), 0.0), double(f.material.z)) : 0.0;
    const glm::dvec3 c = glm::dvec3(f.light_color) *
                         (double(f.light_color.a) * base + double(f.material.x) * std::max(ndl, 0.0) * base + double(f.material.y) * spec);
    return 255.0 * glm::pow(glm::clamp(c, 0.0, 1.0), glm::dvec3(1.0 / 2.2));
}

}  // namespace ranryu::test
