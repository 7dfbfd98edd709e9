// CPU side of the level set (engine/surface/level_set.h): the kernel and iso choice, the ordered float
// bits of the bounds reduction, and the grid placement rule that place_grid.comp implements.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include "support/gl_fixture.h"   // ranryu::test::Random only; no context is made here
#include "surface/level_set.h"

namespace rs = ranryu::surface;

TEST_CASE("level set defaults: a lone particle's surface lies at the particle radius", "[surface]") {
    ranryu::test::Random rng;
    INFO("seed " << rng.seed());
    const float dx = std::exp(rng.uniform(-6.0f, 0.0f));
    const auto s = rs::LevelSetSettings::for_spacing(dx);
    INFO("dx = " << dx);
    CHECK(s.kernel_radius == Approx(1.5 * dx));
    // iso = dx^3 W(dx/2, 1.5 dx) = (8/π)(2/3)^3 (1 - 6 (1/3)^2 (2/3)) = 0.41917..., for any dx.
    const double q = 1.0 / 3.0, expected = 8.0 / std::numbers::pi * std::pow(2.0 / 3.0, 3) * (6 * q * q * (q - 1) + 1);
    CHECK(s.iso == Approx(expected).epsilon(1e-6));
    CHECK(s.iso == Approx(0.41917).epsilon(1e-4));
    // The lone particle's φ = dx^3 W(r) - iso changes sign at r = dx/2.
    const double V = double(dx) * dx * dx;
    CHECK(V * rs::kernel_w(0.499 * dx, s.kernel_radius) > s.iso);
    CHECK(V * rs::kernel_w(0.501 * dx, s.kernel_radius) < s.iso);
    CHECK(rs::kernel_w(s.kernel_radius, s.kernel_radius) == 0.0);
}

TEST_CASE("ordered float bits sort like the floats", "[surface]") {
    ranryu::test::Random rng;
    INFO("seed " << rng.seed());
    for (int i = 0; i < 10000; ++i) {
        const float a = rng.uniform(-1e3f, 1e3f) * std::exp(rng.uniform(-20.0f, 5.0f));
        const float b = rng.uniform(-1e3f, 1e3f) * std::exp(rng.uniform(-20.0f, 5.0f));
        CHECK((a < b) == (rs::ordered_bits(a) < rs::ordered_bits(b)));
        CHECK(rs::from_ordered_bits(rs::ordered_bits(a)) == a);
    }
    CHECK(rs::ordered_bits(-0.0f) < rs::ordered_bits(0.0f));
    CHECK(rs::ordered_bits(-INFINITY) < rs::ordered_bits(-3.0f));
}

TEST_CASE("grid placement covers the particles' support, on the lattice of the node spacing", "[surface]") {
    ranryu::test::Random rng;
    INFO("seed " << rng.seed());
    for (int trial = 0; trial < 200; ++trial) {
        auto s = rs::LevelSetSettings::for_spacing(rng.uniform(0.005f, 0.05f));
        s.max_dims = glm::uvec3(4 + rng.below(200), 4 + rng.below(200), 4 + rng.below(200));
        const glm::vec3 lo(rng.uniform(-2, 2), rng.uniform(-2, 2), rng.uniform(-2, 2));
        const glm::vec3 hi = lo + glm::vec3(rng.uniform(0, 1), rng.uniform(0, 1), rng.uniform(0, 1));
        const auto g = rs::place_grid(lo, hi, s);
        INFO("trial " << trial << ": spacing " << g.spacing << ", dims " << g.dims.x << "x" << g.dims.y << "x" << g.dims.z);
        CHECK(glm::all(glm::lessThanEqual(g.dims, s.max_dims)));
        CHECK(glm::all(glm::greaterThanEqual(g.dims, glm::uvec3(2u))));
        CHECK(g.spacing >= s.node_spacing);
        // Nodes on or beyond [lo - R, hi + R] at both ends (slack: one float rounding of the coordinate).
        const glm::vec3 first = g.origin, last = g.node(g.dims - 1u);
        const float slack = 1e-6f * (1.0f + glm::length(hi));
        CHECK(glm::all(glm::lessThanEqual(first, lo - s.kernel_radius + slack)));
        CHECK(glm::all(glm::greaterThanEqual(last, hi + s.kernel_radius - slack)));
        // Origin on the lattice of multiples of the spacing; the finest spacing when the box fits.
        const glm::vec3 steps = g.origin / g.spacing;
        CHECK(glm::length(steps - glm::round(steps)) < 1e-3f);
        const glm::vec3 need = (hi - lo + 2.0f * s.kernel_radius) / s.node_spacing + 3.0f;
        if (glm::all(glm::lessThanEqual(need, glm::vec3(s.max_dims)))) CHECK(g.spacing == s.node_spacing);
    }
}
