// The mathematical properties of the cubic spline, docs/SPH.md eq. (1), as the reference implements it.
// Every tolerance states where it comes from; each case draws fresh random inputs (seed in INFO).
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <vector>

#include "reference/random.h"
#include "reference/sph_reference.h"

using glm::dvec3;
using ranryu::reference::CubicKernel;
using ranryu::reference::Random;

namespace {
// Support radii spanning the scales a scene can use, plus one random one.
std::vector<double> support_radii(Random& rnd) { return {1e-3, 0.02, 1.0, 37.0, std::exp(rnd.uniform(-7.0, 3.0))}; }

// W′(r) along the unit direction e: ∇W(r·e)·e.
double dW(const CubicKernel& K, double r, const dvec3& e) { return glm::dot(K.gradW(r * e), e); }

dvec3 unit_vector(Random& rnd) { return rnd.rotation() * dvec3(1, 0, 0); }

// k = W(0) = 8/(π h³) and max|∇W| = l/(3h) = 16/(π h⁴) (at q = 1/3): the scales of W and ∇W.
double k_of(double h) { return 8.0 / (std::numbers::pi * h * h * h); }
double grad_scale(double h) { return 16.0 / (std::numbers::pi * h * h * h * h); }

// Composite Simpson's rule for f on [a, b] with n (even) subintervals.
template <class F>
double simpson(F f, double a, double b, int n) {
    const double d = (b - a) / n;
    double s = f(a) + f(b);
    for (int i = 1; i < n; ++i) s += (i % 2 ? 4.0 : 2.0) * f(a + i * d);
    return s * d / 3.0;
}
}  // namespace

TEST_CASE("eq. (1): W integrates to 1 over the ball of radius h") {
    Random rnd;
    INFO("seed " << rnd.seed);
    for (double h : support_radii(rnd)) {
        INFO("h = " << h);
        const CubicKernel K{h};
        // ∫W dV = 4π∫₀ʰ W(r) r² dr, split at the branch point q = ½ so each piece is a quintic in r.
        // Simpson's error is (b−a)/180·δ⁴·max|f⁗|; in q the integrand is 32·q²·w(q) with |f⁗| < 1.2e4, so
        // 200 subintervals per half (δ = 1/400) bound the error by 2e-9: tolerance 1e-8.
        auto f = [&](double r) { return 4.0 * std::numbers::pi * r * r * K.W(r); };
        const double integral = simpson(f, 0.0, h / 2, 200) + simpson(f, h / 2, h, 200);
        CHECK(integral == Approx(1.0).epsilon(0).margin(1e-8));
    }
}

TEST_CASE("eq. (1): W is positive inside its support and exactly zero from h on") {
    Random rnd;
    INFO("seed " << rnd.seed);
    for (double h : support_radii(rnd)) {
        INFO("h = " << h);
        const CubicKernel K{h};
        CHECK(K.W(0.0) == Approx(k_of(h)).epsilon(1e-15));
        for (int s = 0; s < 1000; ++s) {
            const double r = rnd.uniform(0.0, h);
            INFO("r/h = " << r / h);
            CHECK(K.W(r) > 0.0);
        }
        CHECK(K.W(std::nextafter(h, 0.0)) > 0.0);
        CHECK(K.W(h) == 0.0);
        CHECK(K.W(std::nextafter(h, 2 * h)) == 0.0);
        CHECK(K.W(rnd.uniform(h, 10 * h)) == 0.0);
    }
}

TEST_CASE("eq. (1): W and W′ are continuous at q = ½ and at q = 1, where W = W′ = 0") {
    Random rnd;
    INFO("seed " << rnd.seed);
    // One-sided limits at r = (½ ± ε/2)·h and (1 − ε)·h, ε = 1e-10. A smooth W changes across a gap ε·h by at
    // most ε·h·max|W′| = 2ε·k and W′ by ε·h·max|W″| = 12ε·k/h = 6ε·max|∇W|; the tolerances, 1e-8·k and
    // 1e-8·max|∇W|, are 50× and 17× larger, and far below any jump that would matter.
    const double eps = 1e-10;
    for (double h : support_radii(rnd)) {
        INFO("h = " << h);
        const CubicKernel K{h};
        const dvec3 e = unit_vector(rnd);
        const double k = k_of(h), g = grad_scale(h);

        CHECK(K.W(h * (0.5 - eps / 2)) == Approx(K.W(h * (0.5 + eps / 2))).epsilon(0).margin(1e-8 * k));
        CHECK(K.W(h / 2) == Approx(k / 4).epsilon(1e-14));  // both branches give k/4
        CHECK(dW(K, h * (0.5 - eps / 2), e) == Approx(dW(K, h * (0.5 + eps / 2), e)).epsilon(0).margin(1e-8 * g));
        CHECK(dW(K, h / 2, e) == Approx(-3.0 / 4.0 * g).epsilon(1e-14));  // −l/(4h) from both branches

        CHECK(K.W(h * (1 - eps)) == Approx(0.0).margin(1e-8 * k));
        CHECK(dW(K, h * (1 - eps), e) == Approx(0.0).margin(1e-8 * g));
        CHECK(K.gradW(dvec3(0.0, h, 0.0)) == dvec3(0.0));  // |h·e| for a rotated unit e may round below h
        CHECK(K.gradW(h * (1 + 1e-12) * e) == dvec3(0.0));
        CHECK(K.gradW(dvec3(0.0)) == dvec3(0.0));  // W′(0) = 0: the gradient is continuous at r = 0 too
    }
}

TEST_CASE("eq. (1): ∇W(−r) = −∇W(r) exactly") {
    Random rnd;
    INFO("seed " << rnd.seed);
    for (double h : support_radii(rnd)) {
        const CubicKernel K{h};
        for (int s = 0; s < 1000; ++s) {
            const dvec3 r = rnd.in_box(1.2 * h);
            INFO("h = " << h << ", r = (" << r.x << ", " << r.y << ", " << r.z << ")");
            // Exact, not approximate: |−r| = |r| bit for bit, so only the sign of r differs. The symmetric
            // pressure force (4) conserves momentum to round-off because of this.
            CHECK(K.gradW(-r) == -K.gradW(r));
        }
    }
}

TEST_CASE("eq. (1): ∇W equals central differences of W") {
    Random rnd;
    INFO("seed " << rnd.seed);
    for (double h : support_radii(rnd)) {
        const CubicKernel K{h};
        // δ = 1e-6·h: truncation δ²·|W‴|/6 ≈ 1e-12·max|∇W| (W‴ is bounded, W″ continuous across q = ½ and 1),
        // round-off ε·W/δ ≈ 1e-10·max|∇W|. Tolerance: relative 1e-5 of |∇W|, plus 1e-8·max|∇W| where ∇W → 0
        // (near r = 0 and r = h), where a relative error means nothing.
        const double delta = 1e-6 * h;
        for (int s = 0; s < 1000; ++s) {
            const dvec3 r = rnd.in_box(1.1 * h);
            dvec3 fd;
            for (int a = 0; a < 3; ++a) {
                dvec3 step(0.0);
                step[a] = delta;
                fd[a] = (K.W(glm::length(r + step)) - K.W(glm::length(r - step))) / (2 * delta);
            }
            const dvec3 g = K.gradW(r);
            INFO("h = " << h << ", |r|/h = " << glm::length(r) / h << ", ∇W = (" << g.x << ", " << g.y << ", " << g.z
                        << "), differences = (" << fd.x << ", " << fd.y << ", " << fd.z << ")");
            CHECK(glm::length(g - fd) <= 1e-5 * glm::length(g) + 1e-8 * grad_scale(h));
        }
    }
}

TEST_CASE("eq. (1): on a shifted grid, ∫W dV = 1 and ∫∇W dV = 0") {
    Random rnd;
    INFO("seed " << rnd.seed);
    // Midpoint rule over cells of side δ = h/20 whose centres are shifted by a random fraction of a cell,
    // so symmetry does not cancel ∇W exactly. Measured errors at this δ: |∫W − 1| ≈ 2e-8 and
    // |∫∇W| ≈ 5e-7·∫|∇W|. Tolerances: 1e-6 and 1e-5·∫|∇W| (∫|∇W| dV = 4π∫|W′|r² dr = 5.6/h).
    const double h = std::exp(rnd.uniform(-5.0, 2.0));
    INFO("h = " << h);
    const CubicKernel K{h};
    const int n = 20;
    const double d = h / n;
    const dvec3 shift(rnd.uniform(0, 1), rnd.uniform(0, 1), rnd.uniform(0, 1));
    double integral_W = 0.0, integral_abs_grad = 0.0;
    dvec3 integral_grad(0.0);
    for (int i = -n - 1; i <= n; ++i)
        for (int j = -n - 1; j <= n; ++j)
            for (int k = -n - 1; k <= n; ++k) {
                const dvec3 r = (dvec3(i, j, k) + shift) * d;
                integral_W += K.W(glm::length(r)) * d * d * d;
                integral_grad += K.gradW(r) * d * d * d;
                integral_abs_grad += glm::length(K.gradW(r)) * d * d * d;
            }
    CHECK(integral_W == Approx(1.0).epsilon(0).margin(1e-6));
    CHECK(integral_abs_grad == Approx(5.6 / h).epsilon(1e-3));
    CHECK(glm::length(integral_grad) <= 1e-5 * integral_abs_grad);
}

TEST_CASE("eq. (1): Σ_j V_j (x_j − x_i) ⊗ ∇W_ij ≈ I at an interior lattice particle") {
    // The discrete form of ∫(x′ − x) ⊗ ∇_x W(x − x′) dx′ = I (integrate by parts: ∫ r_a ∂_b W dV = −δ_ab),
    // i.e. the SPH gradient of the linear field f = x is exact up to the lattice-sum error. Note the sign:
    // with x_ij = x_i − x_j it is Σ_j V_j x_ij ⊗ ∇W_ij that approximates −I.
    // The lattice is rotated and translated at random; the sum depends only on h/Δx. Measured |M − I|:
    // h/Δx = 4, 6, 8: 5e-5, 2.2e-4, 1.7e-5 (tolerance 5e-4); h/Δx = 2, the simulation's resolution: M = 1.0200·I
    // (tolerance 0.025). Off the diagonal: 1e-12, round-off only, since cubic symmetry makes M exactly ∝ I.
    Random rnd;
    INFO("seed " << rnd.seed);
    struct Case { double ratio, diagonal_tolerance; };
    for (const Case c : {Case{2.0, 0.025}, Case{4.0, 5e-4}, Case{6.0, 5e-4}, Case{8.0, 5e-4}}) {
        const double dx = std::exp(rnd.uniform(-6.0, 0.0));
        const double h = c.ratio * dx;
        INFO("h/Δx = " << c.ratio << ", Δx = " << dx);
        const CubicKernel K{h};
        const int R = static_cast<int>(c.ratio) + 1;  // lattice half-width in cells: covers the support
        const dvec3 xi = rnd.in_box(1.0);
        const glm::dmat3 rotation = rnd.rotation();
        glm::dmat3 M(0.0);  // M[b][a] = Σ_j V_j (x_j − x_i)_a (∇W_ij)_b (glm is column-major)
        for (const dvec3& p : ranryu::reference::lattice(xi - (R + 0.5) * dx, glm::ivec3(2 * R + 1), dx)) {
            const dvec3 xj = xi + rotation * (p - xi);
            M += dx * dx * dx * glm::outerProduct(xj - xi, K.gradW(xi - xj));
        }
        for (int a = 0; a < 3; ++a)
            for (int b = 0; b < 3; ++b) {
                INFO("M[" << a << "][" << b << "] = " << M[b][a]);
                if (a == b) {
                    CHECK(M[b][a] == Approx(1.0).epsilon(0).margin(c.diagonal_tolerance));
                } else {
                    CHECK(M[b][a] == Approx(0.0).margin(1e-12));
                }
            }
    }
}
