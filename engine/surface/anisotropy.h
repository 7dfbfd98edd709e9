#pragma once
// Anisotropic kernels for the level set (Yu & Turk 2013, "Reconstructing surfaces of particle-based
// fluids using anisotropic kernels"; docs/SURFACE.md (S1)-(S8)): per particle, a Laplacian-smoothed
// centre x̄_i (S2) and a stretch of the level set's kernel along the principal axes of the weighted
// covariance of its neighbours (S3)-(S6), so that a flat surface reads flat and a thin sheet keeps
// one kernel's thickness instead of a row of spheres.
//
// The GPU pass is glsl/surface/compute_anisotropy.comp ("surface.anisotropy"); this header holds its
// constants and the double-precision CPU reference the tests compare it with.
#include <cstddef>
#include <span>

#include <glm/glm.hpp>

namespace ranryu::surface {

struct AnisotropySettings {
    float radius = 0.04f;       // r (m): neighbourhood of the weights (S1); 2 dx, one SPH cell
    float lambda = 0.9f;        // λ of the centre smoothing (S2), the paper's value
    float k_s = 1.0f;           // (1/m²) scales the covariance so a full neighbourhood has s = 1 (S5)
    float k_r = 4.0f;           // largest ratio of the longest axis to the others (S5), the paper's value
    float k_n = 0.5f;           // stretch of a particle with fewer than N_ε neighbours (S5), the paper's value
    int n_eps = 6;              // N_ε: neighbours within r (self included) below which a particle is isolated
    float max_stretch = 2.0f;   // s_max: no axis stretches beyond s_max·R (bounds the grid's margin)

    // r = 2 dx and k_s = 1/σ_bulk(dx, r) (bulk_variance), the rest as above.
    static AnisotropySettings for_spacing(float dx);
};

// σ_bulk: the weighted variance per axis (S3) of a full neighbourhood, the cubic lattice of spacing dx
// around a lattice point, weights (S1) with radius r. k_s = 1/σ_bulk makes the bulk's kernel isotropic.
double bulk_variance(double dx, double r);

// Eigen-decomposition of a symmetric 3×3 matrix by cyclic Jacobi rotations (S4): columns of `vectors`
// are unit eigenvectors, `values` the eigenvalues, both sorted by decreasing eigenvalue.
void symmetric_eigen(const glm::dmat3& a, glm::dmat3& vectors, glm::dvec3& values);

// One particle's anisotropy, as compute_anisotropy.comp writes it.
struct ParticleAnisotropy {
    glm::dvec3 centre{0.0};   // x̄_i (S2)
    glm::dmat3 axes{1.0};     // columns: the principal axes a_1, a_2, a_3 (unit)
    glm::dvec3 stretch{1.0};  // s_1, s_2, s_3 (S5): the kernel's support along a_k is s_k·R
    int neighbours = 0;       // N_i: particles within r, itself included
    glm::dmat3 covariance{0.0};   // C_i (S3)
};

// The anisotropy of particle i of `x` (every other particle a candidate neighbour; brute force, double).
ParticleAnisotropy anisotropy_cpu(std::span<const glm::vec4> x, std::size_t i, const AnisotropySettings& a);

// G_i = Σ_k a_k a_kᵀ / max(s_k, floor) (S6), dimensionless: W(d, G) = det(G)·W(|G d|, R) (S7).
glm::dmat3 kernel_matrix(const glm::dmat3& axes, glm::dvec3 stretch, double floor);

}  // namespace ranryu::surface
