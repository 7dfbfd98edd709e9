#include "reference/dfsph_coarse_reference.h"

#include <algorithm>
#include <cmath>

namespace ranryu::reference::dfsph::coarse {
namespace {

const glm::ivec3 kFaces[6] = {{-1, 0, 0}, {1, 0, 0}, {0, -1, 0}, {0, 1, 0}, {0, 0, -1}, {0, 0, 1}};

// The free surface's distance from an active cell's centre, in cells (coarse.glsl).
double surface_coefficient(double phi_c, double phi_a) { return 1.0 / std::clamp(std::min(phi_c, 1.0) - 0.5 + phi_a, 0.1, 1.0); }

}  // namespace

glm::ivec3 Grid::cell_of(glm::dvec3 x) const {
    const glm::ivec3 f = glm::clamp(glm::ivec3(glm::floor((x - fine.origin) / fine.cell)), glm::ivec3(0), fine.dims - 1);
    return f / 2;
}

Cells restrict_residual(const Grid& g, const std::vector<glm::dvec3>& x, const std::vector<double>& residual,
                        const std::vector<glm::dvec3>& boundary, double dx, double rho0, double dt, glm::dvec3 domain_min,
                        glm::dvec3 domain_max) {
    const int n = g.count();
    std::vector<double> sum(n, 0.0);
    std::vector<int> fluid(n, 0), walls(n, 0);
    for (std::size_t i = 0; i < x.size(); ++i) {
        const int c = g.index(g.cell_of(x[i]));
        sum[c] += residual[i], ++fluid[c];
    }
    for (const glm::dvec3& b : boundary) ++walls[g.index(g.cell_of(b))];
    Cells cells{std::vector<double>(n, 0.0), std::vector<double>(n, 0.0), std::vector<double>(n, 0.0)};
    const double H = g.cell(), full = std::pow(H / dx, 3.0);
    for (int k = 0; k < n; ++k) {
        const glm::ivec3 d = g.dims(), c(k % d.x, (k / d.x) % d.y, k / (d.x * d.y));
        if (fluid[k] == 0) {
            const glm::dvec3 centre = g.fine.origin + (glm::dvec3(c) + 0.5) * H;
            const glm::dvec3 margin(0.25 * dx);
            const bool outside = glm::any(glm::lessThan(centre, domain_min - margin)) || glm::any(glm::greaterThan(centre, domain_max + margin));
            cells.phi[k] = walls[k] > 0 || outside ? -1.0 : 0.0;
            continue;
        }
        cells.phi[k] = double(fluid[k]) / std::max(full - double(walls[k]), 1.0);
        cells.rhs[k] = H * H * (sum[k] / fluid[k]) / ((rho0 * dt) * (rho0 * dt));
    }
    return cells;
}

void solve(const Grid& g, Cells& cells, int sweeps, double omega) {
    const glm::ivec3 d = g.dims();
    for (int s = 0; s < sweeps; ++s)
        for (int colour = 0; colour < 2; ++colour)
            for (int k = 0; k < g.count(); ++k) {
                const glm::ivec3 c(k % d.x, (k / d.x) % d.y, k / (d.x * d.y));
                if (((c.x + c.y + c.z) & 1) != colour || !active(cells.phi[k])) continue;
                double sum = cells.rhs[k], diagonal = 0.0;
                for (const glm::ivec3& f : kFaces) {
                    const glm::ivec3 m = c + f;
                    const double phi = g.inside(m) ? cells.phi[g.index(m)] : -1.0;
                    if (solid(phi)) continue;
                    if (active(phi)) sum += cells.e[g.index(m)], diagonal += 1.0;
                    else diagonal += surface_coefficient(cells.phi[k], phi);
                }
                cells.e[k] = diagonal == 0.0 ? 0.0 : cells.e[k] + omega * (sum / diagonal - cells.e[k]);
            }
}

double correction_at(const Grid& g, const Cells& cells, glm::dvec3 x) {
    const glm::dvec3 u = (x - g.fine.origin) / g.cell() - 0.5;
    const glm::ivec3 base(glm::floor(u));
    const glm::dvec3 t = u - glm::dvec3(base);
    double sum = 0.0, weights = 0.0;
    for (int k = 0; k < 8; ++k) {
        const glm::ivec3 o(k & 1, (k >> 1) & 1, k >> 2), c = base + o;
        if (!g.inside(c) || solid(cells.phi[g.index(c)])) continue;
        const glm::dvec3 w3 = glm::mix(1.0 - t, t, glm::dvec3(o));
        const double w = w3.x * w3.y * w3.z;
        weights += w;
        if (active(cells.phi[g.index(c)])) sum += w * cells.e[g.index(c)];
    }
    return weights > 0.0 ? sum / weights : 0.0;
}

}  // namespace ranryu::reference::dfsph::coarse
