// The paddle (engine/sim/boundary.h, sim::Fluid::move_paddle, glsl/sim/fluid/motion.glsl): a
// kinematic sphere. Its projection (docs/SPH.md (9)) against a CPU copy in double on fresh random
// particles, some inside it; its boundary particles placed about the centre with psi_b of eq. (2)
// from the re-sorted boundary; parked, it acts on nothing. Both integrations (WCSPH's
// integrate_particles.comp and DFSPH's integrate_pressure.comp) share keep_out_of_obstacles().
#include "support/gl_fixture.h"
#include "support/sph_rig.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "reference/sph_reference.h"
#include "scene/scene.h"
#include "sim/boundary.h"

namespace {

namespace ref = ranryu::reference;
using ranryu::scene::Scene;

// An open 0.6 m tank with a 0.24 m pool at dx = 0.04 m (h = 0.08 m); the paddle's radius 0.12 m.
Scene paddle_scene(const std::string& solver) {
    Scene s = ranryu::scene::parse(R"({"name": "paddle", "model": "sph",
        "tank": {"min": [0, 0, 0], "max": [0.6, 0.6, 0.6]},
        "particles": {"spacing": 0.04, "blocks": [{"min": [0, 0, 0], "max": [0.6, 0.24, 0.6]}]},
        "sph": {"solver": ")" + solver + R"("}})",
                                   "paddle_test");
    s.paddle_radius = 0.12f;
    return s;
}

// docs/SPH.md (9) in double: the step x1 = x + dt v (no acceleration), then out of the sphere (c, R)
// onto its surface with at least its normal velocity u·n.
struct Moved {
    glm::dvec3 x, v;
    bool projected = false;
};
Moved project(glm::dvec3 x, glm::dvec3 v, double dt, glm::dvec3 c, double R, glm::dvec3 u) {
    Moved m{x + dt * v, v};
    const glm::dvec3 d = m.x - c;
    const double r = glm::length(d);
    if (r >= R) return m;
    const glm::dvec3 n = d / r;
    m.x = c + R * n;
    m.v += std::max(glm::dot(u, n) - glm::dot(v, n), 0.0) * n;
    m.projected = true;
    return m;
}

void clear(const ranryu::gl::Buffer& b) {
    const float zero = 0.0f;
    glBindBuffer(GL_COPY_WRITE_BUFFER, b.id());
    glClearBufferData(GL_COPY_WRITE_BUFFER, GL_R32F, GL_RED, GL_FLOAT, &zero);
    glBindBuffer(GL_COPY_WRITE_BUFFER, 0);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

}  // namespace

TEST_CASE("paddle: the integration's projection moves fluid out of the moving sphere as a CPU copy does", "[paddle]") {
    ranryu::test::Random rng;
    INFO("seed " << rng.seed());
    // DFSPH's time step has no sound speed: from rest, dt is the fixed 1 ms (WCSPH's CFL step is shorter).
    // Fluid::integrate() is integrate_particles.comp whichever the solver; DFSPH's own integration
    // calls the same keep_out_of_obstacles() (the second case runs it).
    ranryu::test::SphRig rig(paddle_scene("dfsph"));
    const double R = rig.scene.paddle_radius, dt = 1e-3;
    // The centre well inside the tank; particles in a cube of half-side 1.2 R about it (0.30 of
    // them inside the sphere: (4/3)pi / 2.4^3), moving at up to 2 m/s, the paddle at up to 1.5 m/s: every particle stays
    // more than a spacing from the walls, where keep_in_tank() leaves it alone.
    const glm::dvec3 c(rng.uniform(0.25f, 0.35f), rng.uniform(0.25f, 0.35f), rng.uniform(0.25f, 0.35f));
    const glm::dvec3 u(rng.uniform(-1.5f, 1.5f), rng.uniform(-1.5f, 1.5f), rng.uniform(-1.5f, 1.5f));
    const std::size_t n = rig.fluid.count();
    std::vector<glm::vec4> x(n), v(n);
    for (std::size_t i = 0; i < n; ++i) {
        // Never within 1e-4 m of the surface after the step: float and double agree on inside and outside.
        for (;;) {
            x[i] = glm::vec4(glm::vec3(c) + 1.2f * float(R) * glm::vec3(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)), 0.0f);
            v[i] = glm::vec4(rng.uniform(-2, 2), rng.uniform(-2, 2), rng.uniform(-2, 2), 0.0f);
            const double r1 = glm::length(glm::dvec3(glm::vec3(x[i])) + dt * glm::dvec3(glm::vec3(v[i])) - c);
            if (std::abs(r1 - R) > 1e-4) break;
        }
    }
    rig.fluid.upload_state(x, v);
    clear(rig.fluid.accelerations());
    rig.fluid.set_fixed_dt(float(dt));
    rig.timer.begin_frame();
    rig.fluid.move_paddle(glm::vec3(c), glm::vec3(u), true);
    rig.fluid.begin_frame(0);
    rig.fluid.choose_time_step();
    rig.fluid.integrate();
    rig.timer.end_frame();
    const std::vector<glm::vec4> xs = rig.read(rig.fluid.positions()), vs = rig.read(rig.fluid.velocities());
    const double used = rig.step().dt;
    rig.finish();
    REQUIRE(used == Approx(dt).epsilon(1e-6));

    // Float: x + dt v and c + R n are each a few ulp of |x| <= 1 m (6e-8 m): 1e-6 m. The normal
    // n = d / r of a projected particle, d = x + dt v - c, carries d's rounding over r (two roundings
    // of coordinates below 0.5 m, 3e-8 m each): dn = 6e-8 m / r, which grows where the step ends near the centre (r/R = 0.04 in one seed of 85),
    // so c + R n adds 2 R dn. The velocity change (u·n - v·n) n: a few ulp of |u - v| <= 6.1 m/s,
    // 1e-5 m/s, plus 2 |u - v| dn from n twice. Each particle is held to its own bound.
    std::size_t projected = 0, worst_x_at = 0, worst_v_at = 0;
    double worst_x = 0.0, worst_v = 0.0, least_r = 1e30, least_gap = 1e30;
    for (std::size_t i = 0; i < n; ++i) {
        const Moved m = project(glm::dvec3(glm::vec3(x[i])), glm::dvec3(glm::vec3(v[i])), used, c, R, u);
        projected += m.projected;
        const glm::dvec3 end = glm::dvec3(glm::vec3(x[i])) + used * glm::dvec3(glm::vec3(v[i]));
        const double dn = m.projected ? 6e-8 / std::max(glm::length(end - c), 1e-9) : 0.0;
        const double bound_x = 1e-6 + 2.0 * R * dn, bound_v = 1e-5 + 2.0 * glm::length(u - glm::dvec3(glm::vec3(v[i]))) * dn;
        const double ex = glm::length(glm::dvec3(glm::vec3(xs[i])) - m.x) / bound_x,
                     ev = glm::length(glm::dvec3(glm::vec3(vs[i])) - m.v) / bound_v;
        if (ex > worst_x) worst_x = ex, worst_x_at = i;
        if (ev > worst_v) worst_v = ev, worst_v_at = i;
        // Analytic: nothing inside, and what was inside leaves no slower than the surface along n.
        const glm::dvec3 d = glm::dvec3(glm::vec3(xs[i])) - c;
        least_r = std::min(least_r, glm::length(d));
        if (m.projected) least_gap = std::min(least_gap, glm::dot(glm::dvec3(glm::vec3(vs[i])) - u, glm::normalize(d)));
    }
    INFO(projected << " of " << n << " projected; worst position error " << worst_x << " of its bound (particle " << worst_x_at
                   << "), worst velocity error " << worst_v << " of its bound (particle " << worst_v_at << ")");
    CHECK(projected > n / 5);        // the cube is 30 % sphere
    CHECK(projected < n);
    CHECK(worst_x <= 1.0);
    CHECK(worst_v <= 1.0);
    CHECK(least_r >= R * (1.0 - 1e-6));
    CHECK(least_gap >= -1e-5);       // (v - u)·n >= 0 for every projected particle
    ranryu::test::require_no_gl_errors();
}

TEST_CASE("paddle: its boundary particles follow the centre with psi from the re-sorted boundary; parked, it acts on nothing", "[paddle]") {
    ranryu::test::Random rng;
    INFO("seed " << rng.seed());
    const std::string solver = GENERATE(as<std::string>(), "wcsph", "dfsph");
    INFO(solver);
    ranryu::test::SphRig rig(paddle_scene(solver));
    const Scene& s = rig.scene;
    const double R = s.paddle_radius;
    const std::vector<glm::vec4> offsets = ranryu::sim::paddle_offsets(s, ranryu::sim::boundary_layers(s.spacing, 2.0f * s.spacing));
    REQUIRE(!offsets.empty());
    // Above the pool (whose top is at 0.24 m): switched on, it appears there and grows to its radius,
    // Δx/4 a substep.
    const glm::dvec3 c(rng.uniform(0.2f, 0.4f), rng.uniform(0.38f, 0.42f), rng.uniform(0.2f, 0.4f));
    rig.sim.set_paddle(true, glm::vec3(c));
    int frame = 0;
    rig.frame(std::uint64_t(frame++));
    REQUIRE(rig.sim.paddle_on());
    REQUIRE(glm::dvec3(rig.sim.paddle_center()) == c);
    CHECK(rig.sim.paddle_scale() < 1.0f);
    while (frame < 20 && rig.sim.paddle_scale() < 1.0f) rig.frame(std::uint64_t(frame++));
    REQUIRE(rig.sim.paddle_scale() == 1.0f);
    std::vector<glm::vec4> b = rig.fluid.boundary().read<glm::vec4>(rig.fluid.boundary_count());

    // The paddle's particles, found by position: c + each offset, once each.
    std::vector<glm::dvec3> all(b.size());
    for (std::size_t k = 0; k < b.size(); ++k) all[k] = glm::dvec3(glm::vec3(b[k]));
    std::vector<bool> used(b.size(), false);
    std::size_t unmatched = 0;
    std::vector<std::size_t> mine;
    for (const glm::vec4& o : offsets) {
        const glm::dvec3 want = c + glm::dvec3(glm::vec3(o));
        std::size_t best = b.size();
        for (std::size_t k = 0; k < b.size(); ++k)
            if (!used[k] && glm::length(all[k] - want) < 1e-5) { best = k; break; }
        if (best == b.size()) { ++unmatched; continue; }
        used[best] = true;
        mine.push_back(best);
    }
    CHECK(unmatched == 0);
    // psi_b = rho0 min(1 / sum_b' W, V_cell) over the whole boundary (eq. (2)); bound as sph_test's, 1e-5 relative.
    const ref::CubicKernel kernel{2.0 * s.spacing};
    const double rho0 = s.sph.rest_density;
    double worst = 0.0;
    std::size_t capped = 0;
    for (std::size_t i = 0; i < mine.size(); ++i) {
        const std::size_t k = mine[i];
        double sum = 0.0;
        for (const glm::dvec3& y : all) sum += kernel.W(glm::length(all[k] - y));
        const double want = rho0 * std::min(1.0 / sum, double(offsets[i].w));
        capped += want == rho0 * double(offsets[i].w);
        worst = std::max(worst, std::abs(double(b[k].w) - want) / want);
    }
    INFO("worst psi error " << worst << " relative; " << capped << " of " << mine.size() << " capped");
    CHECK(worst <= 1e-5);

    // Down into the pool, 0.16 m, at most kPaddleStep spacings a substep: no fluid centre inside it
    // at any frame's end, and it gets there.
    const glm::vec3 low = glm::vec3(c) - glm::vec3(0.0f, 0.16f, 0.0f);
    rig.sim.set_paddle(true, low);
    for (int f = frame; f < frame + 40 && rig.sim.paddle_center() != low && !rig.fluid.instability(); ++f) {
        rig.frame(std::uint64_t(f));
        const glm::dvec3 at(rig.sim.paddle_center());
        const std::vector<glm::vec4> xs = rig.read(rig.fluid.positions());
        double least = 1e30;
        for (const glm::vec4& p : xs) least = std::min(least, glm::length(glm::dvec3(glm::vec3(p)) - at));
        INFO("frame " << f << ": paddle at y = " << at.y << ", nearest fluid centre " << least << " m from it, radius " << R);
        CHECK(least >= R * (1.0 - 1e-6));
    }
    CHECK(rig.sim.paddle_center() == low);

    // Parked: its particles leave for paddle_park(), farther than a support from every fluid particle.
    rig.sim.set_paddle(false, low);
    rig.frame(100);
    CHECK_FALSE(rig.sim.paddle_on());
    b = rig.fluid.boundary().read<glm::vec4>(rig.fluid.boundary_count());
    const glm::dvec3 park(ranryu::sim::paddle_park(s));
    std::size_t parked = 0;
    for (const glm::vec4& p : b) parked += glm::length(glm::dvec3(glm::vec3(p)) - park) <= R + 1e-5;
    CHECK(parked == offsets.size());
    const std::vector<glm::vec4> xs = rig.read(rig.fluid.positions());
    double nearest = 1e30;
    for (const glm::vec4& p : xs) nearest = std::min(nearest, glm::length(glm::dvec3(glm::vec3(p)) - park) - R);
    CHECK(nearest > 2.0 * s.spacing);   // beyond a support h = 2 dx
    rig.finish();
    INFO((rig.fluid.instability() ? rig.fluid.instability()->message() : std::string("stable")));
    CHECK_FALSE(rig.fluid.instability().has_value());
    ranryu::test::require_no_gl_errors();
}
