#include "sim/boundary.h"

#include <algorithm>
#include <cmath>

#include "scene/scene.h"

namespace ranryu::sim {
namespace {

// Lattice coordinates along one axis for the interval [lo, hi]: `inside` sites lo + (i + 1/2) dx
// and `layers` sites beyond each end, at lo - (l + 1/2) dx and hi + (l + 1/2) dx.
struct Axis {
    std::vector<float> at;
    std::vector<int> side;   // -1 below lo, 0 inside, +1 above hi
};
Axis axis(float lo, float hi, float dx, int layers) {
    Axis a;
    for (int l = layers - 1; l >= 0; --l) a.at.push_back(lo - (float(l) + 0.5f) * dx), a.side.push_back(-1);
    const int n = std::max(1, int(std::floor((hi - lo) / dx + 1e-4f)));
    const float pitch = (hi - lo) / float(n);   // fits the interval exactly: no gap at the far wall
    for (int i = 0; i < n; ++i) a.at.push_back(lo + (float(i) + 0.5f) * pitch), a.side.push_back(0);
    for (int l = 0; l < layers; ++l) a.at.push_back(hi + (float(l) + 0.5f) * dx), a.side.push_back(+1);
    return a;
}

}  // namespace

int boundary_layers(float spacing, float support) { return int(std::ceil(support / spacing)) + 1; }

std::vector<glm::vec4> sample_boundary(const scene::Scene& s, int layers) {
    const float dx = s.spacing;
    std::vector<glm::vec4> out;
    // Tank: the shell around the inner box, less the part above the top (open tank).
    const Axis ax = axis(s.tank_min.x, s.tank_max.x, dx, layers), ay = axis(s.tank_min.y, s.tank_max.y, dx, layers),
               az = axis(s.tank_min.z, s.tank_max.z, dx, layers);
    for (std::size_t k = 0; k < az.at.size(); ++k)
        for (std::size_t j = 0; j < ay.at.size(); ++j) {
            if (ay.side[j] > 0) continue;
            for (std::size_t i = 0; i < ax.at.size(); ++i)
                if (ax.side[i] != 0 || ay.side[j] != 0 || az.side[k] != 0) out.emplace_back(ax.at[i], ay.at[j], az.at[k], 0.0f);
        }
    // Obstacles: lattice sites inside the solid within `layers` spacings of its surface.
    const float depth = float(layers) * dx;
    for (const scene::Obstacle& o : s.obstacles) {
        const glm::vec3 lo = o.kind == scene::Obstacle::Kind::box ? o.min : o.center - o.radius;
        const glm::vec3 hi = o.kind == scene::Obstacle::Kind::box ? o.max : o.center + o.radius;
        const glm::ivec3 n = glm::max(glm::ivec3(glm::floor((hi - lo) / dx + 1e-4f)), glm::ivec3(1));
        const glm::vec3 pitch = (hi - lo) / glm::vec3(n);
        for (int k = 0; k < n.z; ++k)
            for (int j = 0; j < n.y; ++j)
                for (int i = 0; i < n.x; ++i) {
                    const glm::vec3 p = lo + (glm::vec3(float(i), float(j), float(k)) + 0.5f) * pitch;
                    float inside;   // distance from p to the surface, positive inside
                    if (o.kind == scene::Obstacle::Kind::sphere) inside = o.radius - glm::length(p - o.center);
                    else {
                        const glm::vec3 d = glm::min(p - o.min, o.max - p);
                        inside = std::min({d.x, d.y, d.z});
                    }
                    if (inside > 0.0f && inside < depth) out.emplace_back(p, 0.0f);
                }
    }
    return out;
}

}  // namespace ranryu::sim
