#include "surface/anisotropy.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace ranryu::surface {

namespace {
double weight(double q, double r) {   // (S1)
    if (q >= r) return 0.0;
    const double t = q / r;
    return 1.0 - t * t * t;
}
}  // namespace

AnisotropySettings AnisotropySettings::for_spacing(float dx) {
    AnisotropySettings a;
    a.radius = 2.0f * dx;
    a.k_s = float(1.0 / bulk_variance(dx, a.radius));
    return a;
}

double bulk_variance(double dx, double r) {
    const int n = int(std::ceil(r / dx));
    double sw = 0.0, swdd = 0.0;
    for (int k = -n; k <= n; ++k)
        for (int j = -n; j <= n; ++j)
            for (int i = -n; i <= n; ++i) {
                const glm::dvec3 d = dx * glm::dvec3(i, j, k);
                const double w = weight(glm::length(d), r);
                sw += w;
                swdd += w * glm::dot(d, d);
            }
    return swdd / sw / 3.0;   // the mean is 0 by symmetry; trace / 3
}

void symmetric_eigen(const glm::dmat3& m, glm::dmat3& vectors, glm::dvec3& values) {
    glm::dmat3 a = m, v(1.0);   // a[col][row]
    for (int sweep = 0; sweep < 50; ++sweep) {
        const double off = a[1][0] * a[1][0] + a[2][0] * a[2][0] + a[2][1] * a[2][1];
        const double diag = a[0][0] * a[0][0] + a[1][1] * a[1][1] + a[2][2] * a[2][2];
        if (off <= 1e-32 * diag || off == 0.0) break;
        for (auto [p, q] : {std::pair{0, 1}, std::pair{0, 2}, std::pair{1, 2}}) {
            const double apq = a[q][p];
            if (apq == 0.0) continue;
            const double theta = (a[q][q] - a[p][p]) / (2.0 * apq);
            const double t = (theta >= 0.0 ? 1.0 : -1.0) / (std::abs(theta) + std::sqrt(theta * theta + 1.0));
            const double c = 1.0 / std::sqrt(t * t + 1.0), s = t * c;
            glm::dmat3 j(1.0);
            j[p][p] = c;
            j[q][q] = c;
            j[q][p] = s;    // row p, column q
            j[p][q] = -s;   // row q, column p
            a = glm::transpose(j) * a * j;
            v = v * j;
        }
    }
    int order[3] = {0, 1, 2};
    std::sort(order, order + 3, [&](int x, int y) { return a[x][x] > a[y][y]; });
    for (int k = 0; k < 3; ++k) {
        values[k] = a[order[k]][order[k]];
        vectors[k] = v[order[k]];
    }
}

ParticleAnisotropy anisotropy_cpu(std::span<const glm::vec4> x, std::size_t i, const AnisotropySettings& s) {
    const double r = s.radius;
    const glm::dvec3 xi(glm::vec3(x[i]));
    double sw = 0.0;
    glm::dvec3 swd(0.0);
    glm::dmat3 swdd(0.0);
    ParticleAnisotropy out;
    for (const glm::vec4& p : x) {
        const glm::dvec3 d = glm::dvec3(glm::vec3(p)) - xi;
        const double q = glm::length(d);
        if (q >= r) continue;
        const double w = weight(q, r);
        ++out.neighbours;
        sw += w;
        swd += w * d;
        swdd += w * glm::outerProduct(d, d);
    }
    const glm::dvec3 mean = swd / sw;   // x_i^w - x_i (S1)
    out.centre = xi + double(s.lambda) * mean;   // (S2)
    out.covariance = swdd / sw - glm::outerProduct(mean, mean);   // (S3)
    if (out.neighbours < s.n_eps) {   // (S5), isolated
        out.axes = glm::dmat3(1.0);
        out.stretch = glm::dvec3(s.k_n);
        return out;
    }
    glm::dvec3 sigma;
    symmetric_eigen(out.covariance, out.axes, sigma);   // (S4)
    const double top = sigma[0];
    for (int k = 0; k < 3; ++k) {
        const double clamped = k == 0 ? top : std::max(sigma[k], top / s.k_r);
        out.stretch[k] = std::min(double(s.k_s) * clamped, double(s.max_stretch));   // (S5)
    }
    return out;
}

glm::dmat3 kernel_matrix(const glm::dmat3& axes, glm::dvec3 stretch, double floor) {
    glm::dmat3 g(0.0);
    for (int k = 0; k < 3; ++k) g += glm::outerProduct(axes[k], axes[k]) / std::max(stretch[k], floor);   // (S6)
    return g;
}

}  // namespace ranryu::surface
