#pragma once
// The CPU reference of the density solve's coarse correction (docs/DFSPH.md (D12)), double precision,
// written for reading; glsl/sim/dfsph/restrict_residual.comp, solve_coarse.comp and
// prolong_correction.comp are compared against it. A correction, as the GPU runs it:
//
//     cells = restrict_residual(grid, x, e, boundary, ...)   // r_c, phi_c, each cell's kind
//     solve(grid, cells, sweeps)                            // red-black SOR of the coarse Poisson problem
//     kappa_i = max(kappa_i + correction_at(grid, cells, x_i), 0)
#include <vector>

#include <glm/glm.hpp>

namespace ranryu::reference::dfsph::coarse {

// The neighbour grid the coarse grid is laid over: its lower corner, cell size h and cells per axis.
struct FineGrid {
    glm::dvec3 origin;
    double cell;
    glm::ivec3 dims;
};

// The coarse grid: cells two fine cells wide.
struct Grid {
    FineGrid fine;
    double cell() const { return 2.0 * fine.cell; }
    glm::ivec3 dims() const { return (fine.dims + 1) / 2; }
    int count() const { const glm::ivec3 n = dims(); return n.x * n.y * n.z; }
    int index(glm::ivec3 c) const { const glm::ivec3 n = dims(); return c.x + n.x * (c.y + n.y * c.z); }
    bool inside(glm::ivec3 c) const { return glm::all(glm::greaterThanEqual(c, glm::ivec3(0))) && glm::all(glm::lessThan(c, dims())); }
    glm::ivec3 cell_of(glm::dvec3 x) const;   // the coarse cell of the fine cell x lies in (clamped to the grid)
};

// Per coarse cell: the correction e_c, the right-hand side H² r_c/(ρ0 dt)², the fluid's fraction φ_c
// of the open volume (−1: solid).
struct Cells {
    std::vector<double> e, rhs, phi;
};
inline bool solid(double phi) { return phi < 0.0; }
inline bool active(double phi) { return phi >= 0.5; }

// (D12)'s restriction: particles x_i with residuals e_i, boundary particles at `boundary`, spacing dx;
// a cell with neither whose centre lies a quarter spacing or more outside [domain_min, domain_max] is solid.
Cells restrict_residual(const Grid& g, const std::vector<glm::dvec3>& x, const std::vector<double>& residual,
                        const std::vector<glm::dvec3>& boundary, double dx, double rho0, double dt, glm::dvec3 domain_min,
                        glm::dvec3 domain_max);

// `sweeps` red-black sweeps of SOR with factor omega from e = 0 (colour 0 then 1 in each sweep).
void solve(const Grid& g, Cells& cells, int sweeps, double omega);

// The correction at x: trilinear between the centres of the eight cells around it, solid ones dropped.
double correction_at(const Grid& g, const Cells& cells, glm::dvec3 x);

}  // namespace ranryu::reference::dfsph::coarse
