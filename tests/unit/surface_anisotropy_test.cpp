// CPU side of the anisotropic kernels (engine/surface/anisotropy.h, docs/SURFACE.md (S1)-(S9)): the
// Jacobi eigen-decomposition against matrices of known spectrum, the stretches' rules on lattice
// neighbourhoods whose shape is known (bulk, flat top, one-particle sheet, lone particle), and the
// CPU pipeline (anisotropy -> level set -> marching cubes) on a pool and a sphere of particles.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "support/gl_fixture.h"   // ranryu::test::Random only; no context is made here
#include "surface/anisotropy.h"
#include "surface/level_set.h"
#include "surface/marching_cubes.h"

namespace rs = ranryu::surface;

namespace {
// A random rotation (from a random unit quaternion).
glm::dmat3 random_rotation(ranryu::test::Random& rng) {
    glm::dvec4 q;
    do q = glm::dvec4(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
    while (glm::length(q) > 1.0 || glm::length(q) < 0.1);
    q = glm::normalize(q);
    const double w = q.w, x = q.x, y = q.y, z = q.z;
    return glm::transpose(glm::dmat3(1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w),   //
                                     2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w),   //
                                     2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)));
}

std::vector<glm::vec4> lattice(glm::ivec3 n, float dx, glm::vec3 corner) {
    std::vector<glm::vec4> x;
    for (int k = 0; k < n.z; ++k)
        for (int j = 0; j < n.y; ++j)
            for (int i = 0; i < n.x; ++i) x.emplace_back(corner + dx * glm::vec3(i, j, k), 0.0f);
    return x;
}
}  // namespace

TEST_CASE("anisotropy: Jacobi recovers a random symmetric matrix's spectrum", "[surface]") {
    ranryu::test::Random rng;
    INFO("seed " << rng.seed());
    for (int t = 0; t < 200; ++t) {
        const glm::dmat3 q = random_rotation(rng);
        glm::dvec3 l(rng.uniform(0, 1), rng.uniform(0, 1), rng.uniform(0, 1));
        if (t % 4 == 0) l.y = l.x;   // degenerate pairs too
        const glm::dmat3 a = q * glm::dmat3(l.x, 0, 0, 0, l.y, 0, 0, 0, l.z) * glm::transpose(q);
        glm::dmat3 v;
        glm::dvec3 e;
        rs::symmetric_eigen(a, v, e);
        // Sorted, the same values, orthonormal vectors, and A v = λ v: all to double round-off (1e-12).
        CHECK(e.x >= e.y);
        CHECK(e.y >= e.z);
        double want[3] = {l.x, l.y, l.z};
        std::sort(want, want + 3, [](double p, double r) { return p > r; });
        for (int k = 0; k < 3; ++k) {
            CHECK(std::abs(e[k] - want[k]) < 1e-12);
            CHECK(glm::length(a * v[k] - e[k] * v[k]) < 1e-12);
            CHECK(std::abs(glm::length(v[k]) - 1.0) < 1e-12);
        }
        CHECK(std::abs(glm::dot(v[0], v[1])) < 1e-12);
    }
}

TEST_CASE("anisotropy: the stretches follow the neighbourhood's shape", "[surface]") {
    ranryu::test::Random rng;
    INFO("seed " << rng.seed());
    const float dx = std::exp(rng.uniform(-6.0f, -1.0f));
    const auto a = rs::AnisotropySettings::for_spacing(dx);
    INFO("dx " << dx);
    CHECK(a.radius == Approx(2.0 * dx));
    // Within a few spacings of the origin: the lattice's float coordinates are then exact to 2^-24
    // of 10 Δx, and the expectations below hold to 1e-5.
    const glm::vec3 corner = dx * glm::vec3(rng.uniform(-5, 5), rng.uniform(-5, 5), rng.uniform(-5, 5));
    const auto block = lattice(glm::ivec3(7), dx, corner);
    const auto at = [&](int i, int j, int k) { return std::size_t(i + 7 * (j + 7 * k)); };

    // Bulk (S5): k_s = 1/σ_bulk makes a full neighbourhood's kernel the isotropic one, centre unmoved.
    const auto bulk = rs::anisotropy_cpu(block, at(3, 3, 3), a);
    // |d|² in {0, 1, 2, 3} dx²; the 6 at 4 dx² lie at r (weight 0), counted or not as the float
    // lattice rounds their distance.
    CHECK(bulk.neighbours >= 27);
    CHECK(bulk.neighbours <= 33);
    for (int k = 0; k < 3; ++k) CHECK(bulk.stretch[k] == Approx(1.0).epsilon(1e-5));
    // (The float lattice is symmetric to the coordinates' rounding, 2^-24 of |x|.)
    CHECK(glm::length(bulk.centre - glm::dvec3(glm::vec3(block[at(3, 3, 3)]))) < 1e-6 * (glm::length(corner) + dx));

    // Flat top (the middle of the top face): the shortest axis is vertical, the centre moves down,
    // the two others are equal by the lattice's symmetry and longer.
    const auto top = rs::anisotropy_cpu(block, at(3, 6, 3), a);
    CHECK(std::abs(top.axes[2].y) == Approx(1.0).epsilon(1e-9));
    CHECK(top.stretch[2] < 0.9 * top.stretch[1]);
    CHECK(top.stretch[0] == Approx(top.stretch[1]).epsilon(1e-5));   // the float lattice: 1e-7 asymmetry
    CHECK(top.centre.y < double(block[at(3, 6, 3)].y) - 0.1 * dx);

    // A one-particle sheet (9 neighbours, 13 with those at r: >= N_ε): thin along its normal, s_3 = s_1 / k_r.
    const auto sheet = lattice(glm::ivec3(7, 1, 7), dx, corner);
    const auto s = rs::anisotropy_cpu(sheet, 3 + 7 * 3, a);
    CHECK(s.neighbours >= 9);
    CHECK(s.neighbours <= 13);
    CHECK(std::abs(s.axes[2].y) == Approx(1.0).epsilon(1e-9));
    CHECK(s.stretch[2] == Approx(s.stretch[0] / a.k_r).epsilon(1e-9));   // σ_3 = 0, clamped (S5)

    // A lone particle and a filament (3 neighbours, 5 with those at r: < N_ε): k_n, isotropic.
    const auto line = lattice(glm::ivec3(7, 1, 1), dx, corner);
    const auto l = rs::anisotropy_cpu(line, 3, a);
    CHECK(l.neighbours >= 3);
    CHECK(l.neighbours <= 5);
    CHECK(l.stretch == glm::dvec3(a.k_n));
    const std::vector<glm::vec4> lone{glm::vec4(corner, 0.0f)};
    CHECK(rs::anisotropy_cpu(lone, 0, a).stretch == glm::dvec3(a.k_n));

    // G (S6) of the bulk is the identity; of the sheet, diag(1/s) in its frame, floored.
    const glm::dmat3 g = rs::kernel_matrix(bulk.axes, bulk.stretch, 0.0);
    for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r) CHECK(std::abs(g[c][r] - (c == r ? 1.0 : 0.0)) < 1e-5);
    const glm::dmat3 gs = rs::kernel_matrix(s.axes, s.stretch, 0.5);
    CHECK(gs[1][1] == Approx(1.0 / std::max(s.stretch[2], 0.5)).epsilon(1e-9));
}

TEST_CASE("level set: a node budget bounds the grid's nodes", "[surface]") {
    ranryu::test::Random rng;
    INFO("seed " << rng.seed());
    for (int t = 0; t < 50; ++t) {
        auto s = rs::LevelSetSettings::for_spacing(0.01f);
        s.max_dims = glm::uvec3(512u);
        s.max_nodes = 1000u + rng.below(100000);
        const glm::vec3 lo(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
        const glm::vec3 hi = lo + glm::vec3(rng.uniform(0, 1), rng.uniform(0, 1), rng.uniform(0, 1));
        const rs::PhiGrid g = rs::place_grid(lo, hi, s);
        INFO("budget " << s.max_nodes << ", grid " << g.dims.x << "x" << g.dims.y << "x" << g.dims.z << " at " << g.spacing);
        CHECK(g.nodes() <= s.max_nodes);
        // Not coarser than needed. The node count is not monotone in h (the origin snaps to multiples
        // of h), but between L/h + 1 and L/h + 3 per axis (L the box with its reach): the bisection
        // ends where the count crosses the budget, so between the spacings at which
        // Π(L/h + 1) and Π(L/h + 3) equal it.
        const glm::vec3 reach(s.kernel_radius + rs::grid_margin(s));
        const glm::dvec3 L = glm::dvec3(hi - lo) + 2.0 * glm::dvec3(reach);
        const auto spacing_for = [&](double extra) {   // Π(L/h + extra) = budget, by bisection in double
            double a = 1e-6, b = 10.0;
            for (int k = 0; k < 200; ++k) {
                const double m = 0.5 * (a + b);
                ((L.x / m + extra) * (L.y / m + extra) * (L.z / m + extra) > double(s.max_nodes) ? a : b) = m;
            }
            return b;
        };
        if (g.spacing > s.node_spacing) {
            CHECK(g.spacing >= spacing_for(1.0) * (1.0 - 1e-4));
            CHECK(g.spacing <= spacing_for(3.0) * (1.0 + 1e-4));
        }
        CHECK(glm::all(glm::lessThanEqual(g.origin, lo - reach + 1e-5f * g.spacing)));   // h·floor(x/h) rounds
        CHECK(glm::all(glm::greaterThanEqual(g.node(g.dims - 1u), hi + reach - 1e-6f)));
    }
}
