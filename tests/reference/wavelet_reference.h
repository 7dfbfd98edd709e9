#pragma once
// CPU reference of the wavelet analysis (docs/METHOD.md §3, engine/turbulence/wavelet.h): in double
// precision, brute force over all pairs (no grid), for reading, not speed.
//
//     û_i = 1/ψ_sum,i · Σ_{j: |x_i − x_j| < R s} (u_j − u_i) · ψ((x_i − x_j)/s),   ê_i = ½|û_i|²
//     ψ(x) = (3 − |x|²)·e^(−|x|²/2),   ψ_sum,i = Σ_{j: |x_i − x_j| < R s} |ψ((x_i − x_j)/s)|   (j = i included)
#include <vector>

#include <glm/glm.hpp>

namespace ranryu::reference {

// The 3-D Mexican hat at |x|² = q2.
double mexican_hat(double q2);

// The continuum response of the truncated analysis to a plane wave u = A sin(k·x) e: û_i =
// gain(ks)·u(x_i) with gain(q) = (ψ̂_R(q) − ψ̂_R(0)) / ∫_{|x|<R}|ψ|, ψ̂_R(q) = 4π∫_0^R ψ(r) sin(qr)/(qr) r² dr
// (a lattice of particles samples the integrals; Simpson's rule here).
double wavelet_gain(double q, double truncation);

struct WaveletResult {
    std::vector<glm::dvec3> u_hat;
    std::vector<double> energy;      // ê_i
    std::vector<double> psi_sum;     // ψ_sum,i
    std::vector<int> terms;          // neighbours summed, i included
};

WaveletResult wavelet_analysis(const std::vector<glm::dvec3>& x, const std::vector<glm::dvec3>& u, double scale,
                               double truncation);

}  // namespace ranryu::reference
