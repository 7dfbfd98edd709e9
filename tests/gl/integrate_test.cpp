// The integrate pass (glsl/sim/integrate.comp) against exact and CPU references:
//     u(t+dt) = u(t) + dt·g,   x(t+dt) = x(t) + dt·u(t+dt)          (semi-implicit Euler)
// then, per axis, a particle past a wall inset by the radius is put on it and its normal velocity
// becomes −e·(the part toward the wall).
#include "support/gl_fixture.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include <glm/glm.hpp>

#include "profile/gpu_timer.h"
#include "shader/source.h"
#include "sim/particles.h"

using ranryu::profile::GpuTimer;
using ranryu::shader::FileSource;
using ranryu::sim::Particles;
namespace gpu = ranryu::gpu;

namespace {

constexpr double kEps = std::numeric_limits<float>::epsilon();   // 2^-23: one ulp at 1.0

// The pass under test with its own timer. Passes run inside a frame.
struct Rig {
    GpuTimer timer;
    Particles particles{FileSource::embedded(), timer};

    void substeps(int n) {
        for (int s = 0; s < n; ++s) {
            timer.begin_frame();
            particles.integrate();
            timer.end_frame();
        }
    }
    std::vector<glm::vec4> x() const { return particles.positions().read<glm::vec4>(particles.count()); }
    std::vector<glm::vec4> u() const { return particles.velocities().read<glm::vec4>(particles.count()); }
};

gpu::SimParams params(glm::vec3 g, glm::vec3 lo, glm::vec3 hi, float dt, float restitution, float radius) {
    gpu::SimParams p{};
    p.gravity = glm::vec4(g, 0.0f);
    p.domain_min = glm::vec4(lo, 0.0f);
    p.domain_max = glm::vec4(hi, 0.0f);
    p.dt = dt;
    p.restitution = restitution;
    p.particle_radius = radius;
    return p;
}

glm::vec3 random_vec(ranryu::test::Random& r, float lo, float hi) {
    return {r.uniform(lo, hi), r.uniform(lo, hi), r.uniform(lo, hi)};
}

// Which way a wall check went on one axis: none, clamped to the low wall, to the high wall.
enum class Wall { none, low, high };

// One substep of integrate.comp in float, the same operations in the same order.
struct CpuStep {
    glm::vec3 x, u;
    std::array<Wall, 3> wall{};
    glm::vec3 unclamped;   // x before the wall checks
};
CpuStep cpu_step(const gpu::SimParams& p, glm::vec3 x0, glm::vec3 u0) {
    CpuStep s;
    s.u = u0 + p.dt * glm::vec3(p.gravity);
    s.x = x0 + p.dt * s.u;
    s.unclamped = s.x;
    const glm::vec3 lo = glm::vec3(p.domain_min) + p.particle_radius;
    const glm::vec3 hi = glm::vec3(p.domain_max) - p.particle_radius;
    for (int a = 0; a < 3; ++a) {
        s.wall[std::size_t(a)] = Wall::none;
        if (s.x[a] < lo[a]) {
            s.x[a] = lo[a];
            s.u[a] = -p.restitution * std::min(s.u[a], 0.0f);
            s.wall[std::size_t(a)] = Wall::low;
        }
        if (s.x[a] > hi[a]) {
            s.x[a] = hi[a];
            s.u[a] = -p.restitution * std::max(s.u[a], 0.0f);
            s.wall[std::size_t(a)] = Wall::high;
        }
    }
    return s;
}

}  // namespace

TEST_CASE("integrate: constant velocity moves x by N·dt·u to float round-off") {
    ranryu::test::context();
    ranryu::test::Random rng;
    INFO("seed " << rng.seed());
    Rig rig;
    // Far from the walls of a 200 m tank; a count that is not a multiple of the workgroup (256).
    const std::size_t n = 256 * (1 + rng.below(2)) + 1 + rng.below(255);
    std::vector<glm::vec4> x0(n), u0(n);
    for (std::size_t i = 0; i < n; ++i) {
        x0[i] = glm::vec4(random_vec(rng, -1.0f, 1.0f), rng.uniform(-5.0f, 5.0f));   // w is carried, unused
        u0[i] = glm::vec4(random_vec(rng, -3.0f, 3.0f), rng.uniform(-5.0f, 5.0f));
    }
    const int steps = 40 + int(rng.below(40));
    const float dt = rng.uniform(0.5e-3f, 4e-3f);
    rig.particles.reset(x0, u0);
    rig.particles.set_params(params(glm::vec3(0.0f), glm::vec3(-100.0f), glm::vec3(100.0f), dt, 0.5f, 0.01f));
    rig.substeps(steps);
    const auto x = rig.x(), u = rig.u();
    INFO(n << " particles, " << steps << " substeps of " << dt << " s");

    for (std::size_t i = 0; i < n; ++i) {
        INFO("particle " << i);
        // g = 0: u + dt·0 is u exactly, and w is copied, so velocities come back bit for bit.
        CHECK(u[i] == u0[i]);
        CHECK(x[i].w == x0[i].w);
        for (int a = 0; a < 3; ++a) {
            const double exact = double(x0[i][a]) + steps * double(dt) * double(u0[i][a]);
            // Each substep rounds dt·u (≤ ½ ulp of |dt·u|) and the sum (≤ ½ ulp of |x|), or one
            // fused rounding: at most ε·(max|x| + |dt·u|) per substep, so N times that in all.
            const double scale = std::max(std::abs(double(x0[i][a])), std::abs(exact)) + std::abs(dt * u0[i][a]);
            const double tol = steps * kEps * scale;
            INFO("axis " << a << ": got " << x[i][a] << ", exact " << exact << ", tolerance " << tol);
            CHECK(std::abs(double(x[i][a]) - exact) <= tol);
        }
    }
    ranryu::test::require_no_gl_errors();
}

TEST_CASE("integrate: from rest under gravity the error is ½·a·t·dt and halves with dt") {
    ranryu::test::context();
    ranryu::test::Random rng;
    INFO("seed " << rng.seed());
    // From rest at x0 = 0 under constant a, exact arithmetic gives u_k = k·dt·a and
    //     x_N = dt²·a·N(N+1)/2 = ½·a·t² + ½·a·t·dt,   t = N·dt,
    // so the error against the analytic ½·a·t² is e(dt) = ½·a·t·dt: first order, e(dt)/e(dt/2) = 2.
    const glm::vec3 a = glm::normalize(random_vec(rng, -1.0f, 1.0f) + glm::vec3(0.0f, 0.0f, 1e-3f)) *
                        rng.uniform(5.0f, 15.0f);
    const float t = rng.uniform(0.3f, 0.6f);
    const int n0 = 16 + int(rng.below(15));
    INFO("a = (" << a.x << ", " << a.y << ", " << a.z << "), t = " << t << " s, N = " << n0 << ", 2N, 4N");

    Rig rig;
    std::vector<double> error;   // |x_N − ½·a·t²| per dt, t fixed
    for (int k = 0; k < 3; ++k) {
        const int steps = n0 << k;
        const float dt = t / float(steps);
        rig.particles.reset({glm::vec4(0.0f)}, {glm::vec4(0.0f)});
        rig.particles.set_params(params(a, glm::vec3(-1e3f), glm::vec3(1e3f), dt, 0.5f, 0.01f));
        rig.substeps(steps);
        const glm::dvec3 x(glm::vec3(rig.x()[0]));
        const double tn = steps * double(dt);   // t as the float dt makes it
        const glm::dvec3 analytic = 0.5 * glm::dvec3(a) * tn * tn;
        const glm::dvec3 lead = 0.5 * glm::dvec3(a) * tn * double(dt);
        // Float round-off in u and x over N substeps stays below 2·N·ε·|x|, and the lead is |x|/N,
        // so round-off/lead ≤ 2·N²·ε ≈ 0.35 % for N ≤ 120: a 1 % tolerance on the lead covers it.
        INFO("dt = " << dt << ": x = (" << x.x << ", " << x.y << ", " << x.z << "), lead ½·a·t·dt = "
                     << glm::length(lead));
        CHECK(glm::length((x - analytic) - lead) <= 0.01 * glm::length(lead));
        // The lead points along a: x runs ahead of the analytic curve.
        CHECK(glm::dot(x - analytic, glm::dvec3(a)) > 0.0);
        error.push_back(glm::length(x - analytic));
    }
    for (int k = 0; k + 1 < 3; ++k) {
        INFO("e(dt)/e(dt/2) at halving " << k << ": " << error[k] / error[k + 1]);
        CHECK(error[std::size_t(k)] / error[std::size_t(k) + 1] == Approx(2.0).margin(0.05));
    }
    ranryu::test::require_no_gl_errors();
}

TEST_CASE("integrate: walls and restitution match a CPU step, substep by substep") {
    ranryu::test::context();
    ranryu::test::Random rng;
    INFO("seed " << rng.seed());
    Rig rig;
    const glm::vec3 lo = random_vec(rng, -0.5f, 0.5f);
    const glm::vec3 hi = lo + random_vec(rng, 0.3f, 0.8f);
    const float radius = rng.uniform(0.002f, 0.02f);
    const float e = rng.uniform(0.1f, 0.95f);
    const float dt = rng.uniform(1e-3f, 4e-3f);
    const glm::vec3 g = random_vec(rng, -12.0f, 12.0f);
    const std::size_t n = 400 + rng.below(400);
    std::vector<glm::vec4> x0(n), u0(n);
    for (std::size_t i = 0; i < n; ++i) {
        glm::vec3 p;
        for (int a = 0; a < 3; ++a) p[a] = rng.uniform(lo[a] + radius, hi[a] - radius);
        x0[i] = glm::vec4(p, rng.uniform(-1.0f, 1.0f));
        u0[i] = glm::vec4(random_vec(rng, -4.0f, 4.0f), rng.uniform(-1.0f, 1.0f));
    }
    const gpu::SimParams p = params(g, lo, hi, dt, e, radius);
    rig.particles.reset(x0, u0);
    rig.particles.set_params(p);
    const int steps = 150 + int(rng.below(100));
    INFO(n << " particles, " << steps << " substeps of " << dt << " s, e = " << e << ", radius " << radius);

    // Each substep starts the CPU step from the GPU's state before it, so round-off never
    // accumulates and the bound is per step: a few ulps of the operands (the GPU may fuse
    // x + dt·u or u + dt·g into one rounding where the CPU rounds twice).
    //   |Δx| ≤ 4ε·(|x| + |dt·u'| + |x'|),   |Δu| ≤ 4ε·(|u| + |dt·g|)      (e < 1)
    // A particle whose unclamped x lies within that bound of a wall plane may go either way on the
    // GPU; there x agrees both ways (the wall and the unclamped x are that close) and u is checked
    // against both outcomes.
    std::array<int, 6> hits{};   // low x, y, z, high x, y, z
    std::vector<glm::vec4> x = x0, u = u0;
    int failures = 0;
    for (int s = 0; s < steps && failures < 10; ++s) {
        rig.substeps(1);
        const auto gx = rig.x(), gu = rig.u();
        for (std::size_t i = 0; i < n && failures < 10; ++i) {
            const CpuStep c = cpu_step(p, glm::vec3(x[i]), glm::vec3(u[i]));
            bool ok = gx[i].w == x[i].w && gu[i].w == u[i].w;
            for (int a = 0; a < 3; ++a) {
                const float free_u = u[i][a] + dt * g[a];   // before the wall checks
                const float tol_x = 4.0f * float(kEps) * (std::abs(x[i][a]) + std::abs(dt * free_u) + std::abs(c.unclamped[a]));
                const float tol_u = 4.0f * float(kEps) * (std::abs(u[i][a]) + std::abs(dt * g[a]));
                ok = ok && std::abs(gx[i][a] - c.x[a]) <= tol_x;
                const float lo_a = lo[a] + radius, hi_a = hi[a] - radius;
                const bool ambiguous = std::abs(c.unclamped[a] - lo_a) <= tol_x || std::abs(c.unclamped[a] - hi_a) <= tol_x;
                // The other outcome: unclamped velocity, or the reflected one.
                const float other_u = c.wall[std::size_t(a)] != Wall::none ? free_u
                                      : c.unclamped[a] <= 0.5f * (lo_a + hi_a) ? -e * std::min(free_u, 0.0f)
                                                                               : -e * std::max(free_u, 0.0f);
                const bool u_ok = std::abs(gu[i][a] - c.u[a]) <= tol_u ||
                                  (ambiguous && std::abs(gu[i][a] - other_u) <= tol_u);
                ok = ok && u_ok;
                if (c.wall[std::size_t(a)] == Wall::low) ++hits[std::size_t(a)];
                if (c.wall[std::size_t(a)] == Wall::high) ++hits[3 + std::size_t(a)];
            }
            if (!ok) {
                ++failures;
                FAIL_CHECK("substep " << s << ", particle " << i << ": GPU x = (" << gx[i].x << ", " << gx[i].y << ", "
                                      << gx[i].z << ") u = (" << gu[i].x << ", " << gu[i].y << ", " << gu[i].z
                                      << "); CPU x = (" << c.x.x << ", " << c.x.y << ", " << c.x.z << ") u = ("
                                      << c.u.x << ", " << c.u.y << ", " << c.u.z << ")");
            }
            // Every particle stays inside the inset tank.
            for (int a = 0; a < 3; ++a)
                if (!(gx[i][a] >= lo[a] + radius && gx[i][a] <= hi[a] - radius)) {
                    ++failures;
                    FAIL_CHECK("substep " << s << ", particle " << i << " left the tank on axis " << a);
                }
        }
        x = gx;
        u = gu;
    }
    // The walls were exercised: each of the six was hit (a test that never bounces checks nothing).
    INFO("wall hits: low " << hits[0] << ' ' << hits[1] << ' ' << hits[2] << ", high " << hits[3] << ' ' << hits[4]
                           << ' ' << hits[5]);
    for (int h : hits) CHECK(h > 0);
    ranryu::test::require_no_gl_errors();
}
