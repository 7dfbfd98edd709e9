#include "reference/wavelet_reference.h"

#include <cmath>

namespace ranryu::reference {

double mexican_hat(double q2) { return (3.0 - q2) * std::exp(-0.5 * q2); }

double wavelet_gain(double q, double R) {
    const int n = 4000;   // Simpson's rule, even n
    const double step = R / n;
    auto simpson = [&](auto f) {
        double s = f(0.0) + f(R);
        for (int k = 1; k < n; ++k) s += (k % 2 ? 4.0 : 2.0) * f(k * step);
        return s * step / 3.0;
    };
    const double pi = 3.14159265358979323846;
    const double hat_q = 4.0 * pi * simpson([&](double r) {
        const double j0 = q * r > 0.0 ? std::sin(q * r) / (q * r) : 1.0;
        return mexican_hat(r * r) * j0 * r * r;
    });
    const double hat_0 = 4.0 * pi * R * R * R * std::exp(-0.5 * R * R);   // ∫_0^R (3 − r²)e^(−r²/2) r² dr = R³e^(−R²/2)
    const double abs_int = 4.0 * pi * simpson([&](double r) { return std::abs(mexican_hat(r * r)) * r * r; });
    return (hat_q - hat_0) / abs_int;
}

WaveletResult wavelet_analysis(const std::vector<glm::dvec3>& x, const std::vector<glm::dvec3>& u, double scale,
                               double truncation) {
    const std::size_t n = x.size();
    WaveletResult out{std::vector<glm::dvec3>(n), std::vector<double>(n), std::vector<double>(n), std::vector<int>(n)};
    for (std::size_t i = 0; i < n; ++i) {
        glm::dvec3 sum(0.0);
        double psi_sum = 0.0;
        int terms = 0;
        for (std::size_t j = 0; j < n; ++j) {
            const glm::dvec3 d = (x[i] - x[j]) / scale;
            const double q2 = glm::dot(d, d);
            if (q2 >= truncation * truncation) continue;
            const double psi = mexican_hat(q2);
            sum += (u[j] - u[i]) * psi;
            psi_sum += std::abs(psi);
            ++terms;
        }
        out.u_hat[i] = sum / psi_sum;
        out.energy[i] = 0.5 * glm::dot(out.u_hat[i], out.u_hat[i]);
        out.psi_sum[i] = psi_sum;
        out.terms[i] = terms;
    }
    return out;
}

}  // namespace ranryu::reference
