// Checks of the CPU reference SPH (tests/reference/) itself, docs/SPH.md eqs. (2)–(8), on fresh random
// inputs (seed in INFO). The GPU passes are compared against this reference, so it has to be right first.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "reference/random.h"
#include "reference/sph_reference.h"

using glm::dvec3;
using namespace ranryu::reference;

namespace {
// The lattice sums of the cubic spline at h = 2Δx, in closed form. With k = 8/(π h³), k·Δx³ = 1/π; the shells
// r/Δx = 0, 1, √2, √3 hold 1, 6, 12, 8 lattice points where W/k = 1, ¼, 2(1 − 1/√2)³, 2(1 − √3/2)³, and
// r ≥ 2Δx = h contributes nothing.
const double kShell2 = 2 * std::pow(1 - 1 / std::numbers::sqrt2, 3);
const double kShell3 = 2 * std::pow(1 - std::numbers::sqrt3 / 2, 3);
// Δx³·Σ_j W(x_i − x_j) over the whole lattice: 1 − 2.75e-5, so a lattice has ρ = ρ0·(1 − 2.75e-5).
const double kLatticeSum = (1 + 6 * 0.25 + 12 * kShell2 + 8 * kShell3) / std::numbers::pi;
// The part of kLatticeSum from one lattice plane at distance Δx: 0.1497.
const double kPlaneSum = (0.25 + 4 * kShell2 + 4 * kShell3) / std::numbers::pi;

Params random_params(Random& rnd) {
    return Params::from_spacing(rnd.uniform(0.005, 0.1), rnd.uniform(500.0, 2000.0), rnd.uniform(5.0, 100.0),
                                std::pow(10.0, rnd.uniform(-6.0, -2.0)), dvec3(0, -rnd.uniform(1.0, 20.0), 0));
}

// lattice() with every point moved by up to ±jitter·Δx along each axis.
std::vector<dvec3> jittered_lattice(Random& rnd, glm::ivec3 n, double spacing, double jitter) {
    std::vector<dvec3> x = lattice(rnd.in_box(1.0), n, spacing);
    for (dvec3& xi : x) xi += rnd.in_box(jitter * spacing);
    return x;
}

// Σ_i m·a_i and Σ_i m·|a_i|, the scale its round-off is measured against.
struct Momentum {
    dvec3 sum{0.0};
    double scale = 0.0;
};
Momentum momentum_rate(const std::vector<dvec3>& a, double mass) {
    Momentum m;
    for (const dvec3& ai : a) {
        m.sum += mass * ai;
        m.scale += mass * glm::length(ai);
    }
    return m;
}
}  // namespace

TEST_CASE("eq. (2): an interior lattice particle has ρ0 times the lattice sum, |ρ/ρ0 − 1| < 3e-5") {
    // The lattice-sum error of this kernel at h = 2Δx is −2.75e-5 (kLatticeSum), not the percent-level error
    // of other kernels or ratios (h/Δx = 2.5: −1.5e-3, 3: +1.8e-3). The lattice is rotated and moved at random;
    // the particles at least 2 cells from its edge see a full kernel of neighbours.
    Random rnd;
    INFO("seed " << rnd.seed);
    const Params p = random_params(rnd);
    INFO("Δx = " << p.spacing << ", ρ0 = " << p.rest_density);
    const int n = 7;
    State fluid;
    const dvec3 centre = rnd.in_box(1.0);
    const glm::dmat3 rotation = rnd.rotation();
    for (const dvec3& x : lattice(centre - 0.5 * n * p.spacing, glm::ivec3(n), p.spacing))
        fluid.x.push_back(centre + rotation * (x - centre));
    fluid.v.assign(fluid.x.size(), dvec3(0.0));

    const Fields f = compute_fields(fluid, {}, {}, p);

    REQUIRE(std::abs(kLatticeSum - 1) < 3e-5);
    for (int k = 2; k < n - 2; ++k)
        for (int j = 2; j < n - 2; ++j)
            for (int i = 2; i < n - 2; ++i) {
                INFO("particle (" << i << ", " << j << ", " << k << ")");
                CHECK(f.density[i + n * (j + n * k)] == Approx(p.rest_density * kLatticeSum).epsilon(1e-12));
            }
    // Every density is below ρ0 (the edges see fewer neighbours), so eq. (3) clamps every pressure to 0 and
    // a resting lattice feels gravity alone, exactly.
    for (size_t i = 0; i < fluid.x.size(); ++i) {
        INFO("particle " << i << ", ρ = " << f.density[i]);
        CHECK(f.pressure[i] == 0.0);
        CHECK(f.accel[i] == p.gravity);
    }
}

TEST_CASE("eq. (2): beside a flat box_boundary wall the capped ψ gives ρ0 as in the interior") {
    // Fluid fills the box on the cell-centred lattice; box_boundary continues that lattice through the walls.
    // Akinci's V_b = 1/Σ_b′ W counts only boundary neighbours, so a wall's surface-layer particle, which lacks
    // the plane of neighbours on the fluid side, would get V_b = Δx³/(kLatticeSum − kPlaneSum) = 1.176·Δx³ and
    // the first fluid layer ρ/ρ0 = kLatticeSum − kPlaneSum + kPlaneSum/(kLatticeSum − kPlaneSum) = 1.0263.
    // Eq. (2) caps V_b at Δx³, the lattice cell, so every layer sees a full lattice: ρ = ρ0·kLatticeSum to 1e-9
    // (round-off at r = h, where W = 0), everywhere in the block, corners included.
    Random rnd;
    INFO("seed " << rnd.seed);
    const Params p = random_params(rnd);
    const glm::ivec3 n(rnd.integer(5, 7), rnd.integer(5, 7), rnd.integer(5, 7));
    const int layers = rnd.integer(2, 3);  // eq. (8): thickness ≥ h = 2Δx
    const int axis = rnd.integer(0, 2);    // the wall: face `axis`, at min (side 0) or max (side 1)
    const int side = rnd.integer(0, 1);
    INFO("Δx = " << p.spacing << ", n = " << n.x << "×" << n.y << "×" << n.z << ", layers = " << layers
                 << ", wall axis " << axis << " side " << side);

    const dvec3 min = rnd.in_box(1.0);
    State fluid;
    fluid.x = lattice(min, n, p.spacing);
    fluid.v.assign(fluid.x.size(), dvec3(0.0));
    const std::vector<dvec3> boundary = box_boundary(min, min + dvec3(n) * p.spacing, p.spacing, layers);
    const Fields f = compute_fields(fluid, boundary, boundary_psi(boundary, p), p);

    // The particles of the first and second layer at the centre of the wall, ≥ 2.5Δx from the other walls.
    auto at_layer = [&](int layer) {
        glm::ivec3 c = n / 2;
        c[axis] = side == 0 ? layer : n[axis] - 1 - layer;
        return f.density[c.x + n.x * (c.y + n.y * c.z)];
    };
    const double uncapped_first = kLatticeSum - kPlaneSum + kPlaneSum / (kLatticeSum - kPlaneSum);
    CHECK(uncapped_first == Approx(1.02633).epsilon(1e-5));   // what the cap removes
    CHECK(at_layer(0) == Approx(p.rest_density * kLatticeSum).epsilon(1e-9));
    CHECK(at_layer(1) == Approx(p.rest_density * kLatticeSum).epsilon(1e-9));
    for (double rho : f.density) CHECK(rho == Approx(p.rest_density * kLatticeSum).epsilon(1e-9));
}

TEST_CASE("eq. (4): fluid–fluid pressure forces conserve momentum to round-off") {
    // Each pair's terms are exact negatives (p_i/ρ_i² + p_j/ρ_j² is symmetric, ∇W antisymmetric bit for bit),
    // so only the summation order rounds: tolerance |Σ m·a_i| ≤ 1e-13·Σ m·|a_i| (measured ≈ 1e-16).
    Random rnd;
    INFO("seed " << rnd.seed);
    const Params p = random_params(rnd);
    const std::vector<dvec3> x = jittered_lattice(rnd, glm::ivec3(8), p.spacing, 0.3);
    std::vector<double> density(x.size());
    for (double& rho : density) rho = p.rest_density * rnd.uniform(1.0, 1.05);
    const std::vector<double> pressure = pressures(density, p);

    const Momentum m = momentum_rate(pressure_accelerations(x, density, pressure, {}, {}, p), p.mass);
    INFO("|Σ m·a| = " << glm::length(m.sum) << ", Σ m·|a| = " << m.scale);
    CHECK(m.scale > 0.0);
    CHECK(glm::length(m.sum) <= 1e-13 * m.scale);
}

TEST_CASE("eq. (4): a boundary particle with ψ_b = m pushes like half a fluid particle of equal p/ρ²") {
    // Akinci et al. 2012, eq. 10 (and SPlisHSPlasH) mirror p_i/ρ_i² once: −ψ_b·(p_i/ρ_i²)·∇W, against the fluid
    // pair's −m·(p_i/ρ_i² + p_j/ρ_j²)·∇W. So the same neighbours, as fluid with i's density and pressure, push
    // i exactly twice as hard as they do as boundary with ψ_b = m. Tolerance 1e-12 relative (round-off).
    Random rnd;
    INFO("seed " << rnd.seed);
    const Params p = random_params(rnd);
    const std::vector<dvec3> others = jittered_lattice(rnd, glm::ivec3(4), p.spacing, 0.3);
    const dvec3 xi = others[21] + rnd.in_box(0.5 * p.spacing);  // inside the block, near its centre
    const double rho = p.rest_density * rnd.uniform(1.0, 1.05);

    std::vector<dvec3> all{xi};
    all.insert(all.end(), others.begin(), others.end());
    const std::vector<double> density(all.size(), rho), pressure = pressures(density, p);
    const dvec3 as_fluid = pressure_accelerations(all, density, pressure, {}, {}, p)[0];
    const dvec3 as_boundary = pressure_accelerations({xi}, {rho}, {pressure[0]}, others,
                                                     std::vector<double>(others.size(), p.mass), p)[0];
    INFO("fluid (" << as_fluid.x << ", " << as_fluid.y << ", " << as_fluid.z << "), boundary (" << as_boundary.x
                   << ", " << as_boundary.y << ", " << as_boundary.z << ")");
    CHECK(glm::length(as_fluid) > 0.0);
    CHECK(glm::length(as_fluid - 2.0 * as_boundary) <= 1e-12 * glm::length(as_fluid));
}

TEST_CASE("eq. (5): viscosity conserves momentum and dissipates kinetic energy") {
    // eq. (5) weighs pair (i, j) by 2m/(ρ_i + ρ_j), symmetric in i and j, so each pair's terms are exact
    // negatives and momentum is conserved at any densities (random here, ±5 %). Tolerance as for eq. (4):
    // 1e-13·Σ m·|a^ν|. dE/dt = Σ m·v_i·a_i^ν = 10ν·Σ_{i<j} (2m²/(ρ_i+ρ_j))·(v_ij·x_ij)²·W′/(|x_ij|·(|x_ij|² +
    // 0.01h²)) ≤ 0 since W′ ≤ 0; for random velocities it is strictly negative.
    Random rnd;
    INFO("seed " << rnd.seed);
    const Params p = random_params(rnd);
    const std::vector<dvec3> x = jittered_lattice(rnd, glm::ivec3(8), p.spacing, 0.3);
    std::vector<dvec3> v(x.size());
    for (dvec3& vi : v) vi = rnd.in_box(1.0);
    std::vector<double> density(x.size());
    for (double& d : density) d = p.rest_density * rnd.uniform(0.95, 1.05);

    const std::vector<dvec3> a = viscosity_accelerations(x, v, density, p);
    const Momentum m = momentum_rate(a, p.mass);
    double dE_dt = 0.0;
    for (size_t i = 0; i < x.size(); ++i) dE_dt += p.mass * glm::dot(v[i], a[i]);
    INFO("|Σ m·a| = " << glm::length(m.sum) << ", Σ m·|a| = " << m.scale << ", dE/dt = " << dE_dt);
    CHECK(m.scale > 0.0);
    CHECK(glm::length(m.sum) <= 1e-13 * m.scale);
    CHECK(dE_dt < 0.0);
}

TEST_CASE("eq. (5) for two particles of different density, written out") {
    // Pins the exact form: the pair (i, j) is weighed by 2m/(ρ_i + ρ_j). Tolerance 1e-12 relative.
    Random rnd;
    INFO("seed " << rnd.seed);
    const Params p = random_params(rnd);
    const dvec3 x0 = rnd.in_box(1.0);
    const std::vector<dvec3> x_pair{x0, x0 - rnd.rotation() * dvec3(rnd.uniform(0.05, 0.95) * p.h, 0, 0)};
    const std::vector<dvec3> v{rnd.in_box(1.0), rnd.in_box(1.0)};
    const std::vector<double> density{p.rest_density * rnd.uniform(0.9, 1.1), p.rest_density * rnd.uniform(0.9, 1.1)};

    const dvec3 xij = x_pair[0] - x_pair[1], vij = v[0] - v[1];
    const double r = glm::length(xij), q = r / p.h;
    const double dW = q <= 0.5 ? 48 / (std::numbers::pi * std::pow(p.h, 4)) * q * (3 * q - 2)
                               : -48 / (std::numbers::pi * std::pow(p.h, 4)) * (1 - q) * (1 - q);
    const double scalar = 10 * p.viscosity * glm::dot(vij, xij) / (r * r + 0.01 * p.h * p.h) * dW / r;
    const std::vector<dvec3> a = viscosity_accelerations(x_pair, v, density, p);
    const double weight = 2.0 * p.mass / (density[0] + density[1]);
    CHECK(glm::length(a[0] - weight * scalar * xij) <= 1e-12 * glm::length(a[0]));
    CHECK(glm::length(a[1] + weight * scalar * xij) <= 1e-12 * glm::length(a[1]));
}

TEST_CASE("eq. (5): a uniform velocity field has no viscous acceleration") {
    // v_ij = v − v = 0 exactly, so a^ν = 0 exactly (Galilean invariance), whatever the densities.
    Random rnd;
    INFO("seed " << rnd.seed);
    const Params p = random_params(rnd);
    State fluid;
    fluid.x = jittered_lattice(rnd, glm::ivec3(7), p.spacing, 0.3);
    fluid.v.assign(fluid.x.size(), rnd.in_box(10.0));
    const Fields f = compute_fields(fluid, {}, {}, p);
    for (size_t i = 0; i < fluid.x.size(); ++i) {
        INFO("particle " << i);
        CHECK(f.accel_viscosity[i] == dvec3(0.0));
    }
}

TEST_CASE("eq. (5): for a divergence-free field, a^ν → C·ν∇²v, C = 0.963 the bias of the 0.01·h² term") {
    // v = e1·(e2·x)², e1 ⊥ e2, has ∇·v = 0 and ν∇²v = 2ν·e1. In the continuum, eq. (5) at x = 0 is
    //     a^ν = 10ν·e1·∫ −(e1·r)²(e2·r)²·W′/(|r|·(|r|² + η)) dV = 2ν·C·e1,
    //     C = −(4π/3)·∫₀ʰ r⁵·W′(r)/(r² + η) dr   (∫(e1·r)²(e2·r)² dΩ = 4π r⁴/15;  C = 1 for η = 0, as ∫r³W′ dr = −3/(4π)),
    // with η = 0.01·h². A lattice sum reaches this only when the kernel spans many cells: at h = 2Δx,
    // a^ν·e1/(2ν) ranges over 0.70–1.27 with the lattice's orientation, with a spurious part ⊥ e1 of up to 0.33·2ν. So this case uses h = 6Δx, a random rotation of lattice and field, and the particles
    // within h of the centre. Measured over 200 orientations: a^ν·e1/(2νC) ∈ [0.9991, 1.0010], |a^ν ⊥ e1| ≤ 1e-3·2ν.
    // Tolerances: 0.5 % and 0.5 %·2ν. C comes from Simpson's rule split at h/2, 2×200 intervals (error ≪ 1e-6).
    Random rnd;
    INFO("seed " << rnd.seed);
    Params p = random_params(rnd);
    p.h = 6 * p.spacing;  // m = ρ0·Δx³ and ρ = ρ0 below: V_j = Δx³
    INFO("Δx = " << p.spacing << ", ν = " << p.viscosity);
    const CubicKernel K{p.h};
    const double eta = 0.01 * p.h * p.h;
    auto integrand = [&](double r) { return std::pow(r, 5) * K.gradW(dvec3(r, 0, 0)).x / (r * r + eta); };
    auto simpson = [](auto f, double a, double b, int n) {
        const double d = (b - a) / n;
        double sum = f(a) + f(b);
        for (int i = 1; i < n; ++i) sum += (i % 2 ? 4.0 : 2.0) * f(a + i * d);
        return sum * d / 3.0;
    };
    const double C = -4.0 * std::numbers::pi / 3.0 *
                     (simpson(integrand, 0.0, p.h / 2, 200) + simpson(integrand, p.h / 2, p.h, 200));
    CHECK(C == Approx(0.963).epsilon(1e-3));

    const dvec3 centre = rnd.in_box(1.0);
    const glm::dmat3 rotation = rnd.rotation();
    std::vector<dvec3> x{centre};  // particle 0 is the centre
    for (const dvec3& q : lattice(centre - 7.5 * p.spacing, glm::ivec3(15), p.spacing))
        if (q != centre && glm::length(q - centre) < p.h) x.push_back(centre + rotation * (q - centre));
    const glm::dmat3 frame = rnd.rotation();
    const dvec3 e1 = frame[0], e2 = frame[1];
    std::vector<dvec3> v(x.size());
    for (size_t i = 0; i < x.size(); ++i) v[i] = e1 * std::pow(glm::dot(e2, x[i] - centre), 2);
    const std::vector<double> density(x.size(), p.rest_density);

    const dvec3 a = viscosity_accelerations(x, v, density, p)[0];
    const double along = glm::dot(a, e1);
    INFO("a·e1/(2νC) = " << along / (2 * p.viscosity * C) << ", |a ⊥ e1|/(2ν) = "
                         << glm::length(a - along * e1) / (2 * p.viscosity));
    CHECK(along == Approx(2 * p.viscosity * C).epsilon(5e-3));
    CHECK(glm::length(a - along * e1) <= 5e-3 * 2 * p.viscosity);
}

TEST_CASE("neighbours() lists exactly the j with |x_i − x_j| < h, sorted, symmetric") {
    Random rnd;
    INFO("seed " << rnd.seed);
    // 500 random points in a cube of side 4h: about 30 neighbours each, fewer near its faces.
    const double h = rnd.uniform(0.01, 1.0);
    std::vector<dvec3> x(500);
    for (dvec3& xi : x) xi = rnd.in_box(2 * h);
    const auto nb = neighbours(x, h);
    REQUIRE(nb.size() == x.size());
    for (uint32_t i = 0; i < x.size(); ++i) {
        INFO("particle " << i);
        CHECK(std::is_sorted(nb[i].begin(), nb[i].end()));
        CHECK(std::adjacent_find(nb[i].begin(), nb[i].end()) == nb[i].end());
        for (uint32_t j = 0; j < x.size(); ++j) {
            const bool listed = std::binary_search(nb[i].begin(), nb[i].end(), j);
            const bool naive = glm::dot(x[i] - x[j], x[i] - x[j]) < h * h;
            const bool mirrored = std::binary_search(nb[j].begin(), nb[j].end(), i);
            if (listed != naive || listed != mirrored)
                FAIL_CHECK("j = " << j << ": listed " << listed << ", |x_ij| < h " << naive << ", i listed for j "
                                  << mirrored << ", |x_ij|/h = " << glm::length(x[i] - x[j]) / h);
        }
        CHECK(std::binary_search(nb[i].begin(), nb[i].end(), i));
    }

    // On a lattice the shells r/Δx = 0, 1, √2, √3, 2 hold 1, 6, 12, 8, 6 points, so an interior particle has 27
    // neighbours for h = 1.9Δx and 33 for h = 2.1Δx. (h = 2Δx itself is avoided: lattice distances equal to h
    // fall either side of it by rounding; W and ∇W vanish there, so only neighbour counts are affected.)
    const double dx = rnd.uniform(0.01, 1.0);
    const std::vector<dvec3> grid = lattice(rnd.in_box(1.0), glm::ivec3(5), dx);
    const size_t centre = 2 + 5 * (2 + 5 * 2);
    CHECK(neighbours(grid, 1.9 * dx)[centre].size() == 27);
    CHECK(neighbours(grid, 2.1 * dx)[centre].size() == 33);
}

TEST_CASE("eq. (6): constant acceleration over n steps matches the closed-form symplectic Euler sum exactly") {
    // v_n = v_0 + n·Δt·a and x_n = x_0 + n·Δt·v_0 + n(n+1)/2·Δt²·a (x advances with the updated v). The inputs are
    // dyadic rationals (Δt = 2^−k, a, v_0, x_0 with ≤ 6 fractional bits) small enough that every intermediate
    // fits in 53 bits, so both sides are exact and are compared with ==.
    Random rnd;
    INFO("seed " << rnd.seed);
    const int steps = rnd.integer(1, 100);
    const double dt = std::ldexp(1.0, -rnd.integer(3, 8));
    INFO(steps << " steps of " << dt);
    auto dyadic = [&](int range, int bits) {
        return dvec3(rnd.integer(-range, range), rnd.integer(-range, range), rnd.integer(-range, range)) /
               std::ldexp(1.0, bits);
    };
    State s;
    Fields f;
    for (int i = 0; i < 20; ++i) {
        s.x.push_back(dyadic(1024, 6));
        s.v.push_back(dyadic(64, 4));
        f.accel.push_back(dyadic(64, 3));
    }
    const State start = s;
    for (int n = 0; n < steps; ++n) step(s, f, dt);
    const double N = steps;
    for (size_t i = 0; i < s.x.size(); ++i) {
        INFO("particle " << i);
        CHECK(s.v[i] == start.v[i] + N * dt * f.accel[i]);
        CHECK(s.x[i] == start.x[i] + N * dt * start.v[i] + (N * (N + 1) / 2) * (dt * dt) * f.accel[i]);
    }
}

TEST_CASE("eq. (7): the time step is the least of the CFL, force and frame limits") {
    Random rnd;
    INFO("seed " << rnd.seed);
    const Params p = random_params(rnd);
    const double v_max = rnd.uniform(0.0, 10.0);
    const double cfl = 0.4 * p.spacing / (p.speed_of_sound + v_max);
    CHECK(cfl_dt(p, v_max, 0.0, 1.0) == Approx(cfl).epsilon(1e-15));  // no acceleration: no force limit
    const double a_max = 1e6 * p.spacing / (cfl * cfl);                // makes 0.25·√(Δx/a_max) = cfl/4000
    CHECK(cfl_dt(p, v_max, a_max, 1.0) == Approx(0.25 * std::sqrt(p.spacing / a_max)).epsilon(1e-15));
    CHECK(cfl_dt(p, v_max, 0.0, cfl / 3) == cfl / 3);
    CHECK(max_norm({dvec3(1, 2, 2), dvec3(0, -4, 0), dvec3(0.5)}) == 4.0);
    CHECK(max_norm({}) == 0.0);
}

TEST_CASE("Params::from_spacing and eq. (3): h = 2Δx, m = ρ0·Δx³, p = max(0, B·((ρ/ρ0)^7 − 1)), B = ρ0·c²/7") {
    Random rnd;
    INFO("seed " << rnd.seed);
    const Params p = random_params(rnd);
    CHECK(p.h == 2 * p.spacing);
    CHECK(p.mass == Approx(p.rest_density * std::pow(p.spacing, 3)).epsilon(1e-15));
    CHECK(p.B() == Approx(p.rest_density * p.speed_of_sound * p.speed_of_sound / 7).epsilon(1e-15));
    CHECK(tait_pressure(p.rest_density, p) == 0.0);
    CHECK(tait_pressure(0.9 * p.rest_density, p) == 0.0);  // clamped: no tension
    const double ratio = rnd.uniform(1.0, 1.1);
    CHECK(tait_pressure(ratio * p.rest_density, p) == Approx(p.B() * (std::pow(ratio, 7) - 1)).epsilon(1e-12));
    // 1 % compression, the δρ/ρ ≈ (v/c)² of c = 10·v_max: p = (1.01⁷ − 1)·B = 0.0721·B.
    CHECK(tait_pressure(1.01 * p.rest_density, p) == Approx(0.0721 * p.B()).epsilon(1e-3));
}
