// The impact-pressure case's measurements (engine/validation/cases.h): the wall sensor's reading from a
// frame's particles (probe_pressure) and a sensor's comparisons with the experiment (compare_sensor), on
// inputs whose answers are known in closed form.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include <glm/glm.hpp>

#include "support/gl_fixture.h"   // ranryu::test::Random only; no context is made here
#include "validation/cases.h"

namespace validation = ranryu::validation;

namespace {
constexpr double kDx = 0.01;

// A cubic lattice of spacing kDx around (x0, y0, z0), `n` particles each way either side, with the
// pressure field p(x) in Density.y.
template <class Field>
void lattice(std::vector<glm::vec4>& x, std::vector<glm::vec4>& d, glm::dvec3 c, int n, Field p) {
    for (int i = -n; i <= n; ++i)
        for (int j = -n; j <= n; ++j)
            for (int k = -n; k <= n; ++k) {
                const glm::dvec3 q = c + kDx * glm::dvec3(i, j, k);
                x.emplace_back(glm::vec3(q), 1.0f);
                d.emplace_back(1000.0f, float(p(q)), 0.0f, 0.0f);
            }
}
}  // namespace

TEST_CASE("impact pressure: the probe averages the pressure beside it", "[validation][unit]") {
    ranryu::test::Random rng;
    INFO("seed " << rng.seed());
    auto u = [&](ranryu::test::Random& r) { return double(r.uniform(-1.0f, 1.0f)); };
    const glm::dvec3 c(0.5 + 0.01 * u(rng), 0.2 + 0.01 * u(rng), 0.07);
    validation::Probe probe{c.x, c.y, c.z - 0.025, c.z + 0.025, 2.0 * kDx};   // the strip: five layers in z
    std::vector<glm::vec4> x, d;

    // A constant pressure reads exactly (Shepard's normalisation), to float's rounding of the values.
    const double p0 = 1000.0 + 500.0 * u(rng);
    lattice(x, d, c, 4, [&](glm::dvec3) { return p0; });
    CHECK(validation::probe_pressure(probe, x, d) == Approx(p0).epsilon(1e-6));

    // A linear field on a lattice symmetric about the probe: the weights are even in (x − x_p, y − y_p),
    // so the odd part averages to zero and the reading is the field at the probe. Float positions and
    // pressures round each to 6e-8 relative: 1e-5 of the field's span.
    x.clear(), d.clear();
    const double a = 2000.0, bx = 3000.0 * u(rng), by = -9810.0, bz = 5000.0 * u(rng);
    auto linear = [&](glm::dvec3 q) { return a + bx * (q.x - c.x) + by * (q.y - c.y) + bz * (q.z - c.z); };
    lattice(x, d, c, 4, linear);
    CHECK(validation::probe_pressure(probe, x, d) == Approx(a).margin(1e-5 * 9810.0 * 0.08));

    // Whatever lies off the strip, a support or more away in x-y, or parked, is not read.
    const std::size_t before = x.size();
    const double reading = validation::probe_pressure(probe, x, d);
    x.emplace_back(glm::vec3(c.x, c.y, probe.z_hi + 0.001), 1.0f), d.emplace_back(1000.0f, 1e7f, 0.0f, 0.0f);                 // off the strip
    x.emplace_back(glm::vec3(c.x + 2.0 * kDx + 1e-4, c.y, c.z), 1.0f), d.emplace_back(1000.0f, 1e7f, 0.0f, 0.0f);             // beyond the support
    x.emplace_back(glm::vec3(c.x + 0.1 * kDx, c.y, c.z), -1.0f), d.emplace_back(1000.0f, 1e7f, 0.0f, 0.0f);                   // parked
    REQUIRE(x.size() == before + 3);
    CHECK(validation::probe_pressure(probe, x, d) == reading);

    // One particle inside does count: the reading moves towards its pressure.
    x.emplace_back(glm::vec3(c.x + 0.1 * kDx, c.y, c.z), 1.0f), d.emplace_back(1000.0f, 1e7f, 0.0f, 0.0f);
    CHECK(validation::probe_pressure(probe, x, d) > reading + 1000.0);

    // With a face: nothing behind it is read (a probe placed on the wrong side would read through it).
    validation::Probe faced = probe;
    faced.face = c.x - 0.5 * kDx, faced.side = 1.0;   // the fluid at larger x; the lattice's column at c.x - kDx lies behind
    std::vector<glm::vec4> xf, df;
    lattice(xf, df, c, 4, [&](glm::dvec3 q) { return q.x < faced.face ? 1e7 : p0; });
    CHECK(validation::probe_pressure(faced, xf, df) == Approx(p0).epsilon(1e-6));
    CHECK(validation::probe_pressure(probe, xf, df) > 2.0 * p0);   // without the face the column behind it counts

    // Dry: no particle within the support reads zero.
    std::vector<glm::vec4> far{glm::vec4(glm::vec3(c) + glm::vec3(0.05f, 0.0f, 0.0f), 1.0f)}, far_d{glm::vec4(1000.0f, 5000.0f, 0.0f, 0.0f)};
    CHECK(validation::probe_pressure(probe, far, far_d) == 0.0);
}

TEST_CASE("impact pressure: a sensor's impact, peak and run-up against the experiment", "[validation][unit]") {
    // The experiment: dry, a ramp to 2 over T in [2.4, 2.5], down to 0.6 by T = 3 and 0.6 after; the
    // simulation the same shape `shift` later with its run-up at `plateau`, sampled every 0.005 (a frame
    // at this scale). Every kink of the simulated series falls on one of its samples, so its linear
    // interpolation is the function itself: the comparisons have closed forms, summed here with the
    // trapezoid rule's weights over the experiment's samples in the window (every 1/400: half a weight at
    // the window's ends) from the function, not from the series.
    auto f = [](double t, double shift, double plateau) {
        const double T = t - shift;
        if (T < 2.4) return 0.0;
        if (T < 2.5) return 20.0 * (T - 2.4);
        if (T < 3.0) return 2.0 + (plateau - 2.0) * (T - 2.5) / 0.5;
        return plateau;
    };
    auto series = [&](double shift, double plateau, int per_unit) {
        std::vector<std::pair<double, double>> s;
        for (int k = 1; k <= 7 * per_unit; ++k) s.emplace_back(double(k) / per_unit, f(double(k) / per_unit, shift, plateau));
        return s;
    };
    validation::ImpactPressureResult::Sensor s;
    s.name = "P1";
    s.measured = series(0.0, 0.6, 400);
    s.simulated = series(0.1, 0.7, 200);
    validation::compare_sensor(s, 3.0, 5.5);
    REQUIRE(s.onset_measured);
    REQUIRE(s.onset_simulated);
    CHECK(*s.onset_measured == Approx(2.4 + 0.25 / 20.0).margin(1e-9));   // level 0.25 on the ramp
    CHECK(*s.onset_simulated == Approx(2.5 + 0.25 / 20.0).margin(1e-9));
    CHECK(s.peak_measured == Approx(2.0).margin(1e-9));                   // the ramp's top is a sample
    CHECK(s.peak_simulated == Approx(2.0).margin(1e-9));
    int n = 0;
    double weight = 0.0, mean = 0.0, square = 0.0;
    for (int k = 1200; k <= 2200; ++k) {   // the experiment's samples in T = [3, 5.5]
        const double t = k / 400.0, d = f(t, 0.1, 0.7), w = (k == 1200 || k == 2200) ? 0.5 : 1.0;
        ++n, weight += w, mean += w * d, square += w * (d - 0.6) * (d - 0.6);
    }
    CHECK(s.compared == n);
    CHECK(s.mean_measured == Approx(0.6).margin(1e-12));
    CHECK(s.mean_simulated == Approx(mean / weight).margin(1e-9));
    CHECK(s.rms_error == Approx(std::sqrt(square / weight)).margin(1e-9));

    // Time, not samples: an experiment sampled ten times as densely over half the window weighs that half
    // as much as the other. A step from 0.6 to 0.8 at T = 4.25 with the samples dense before it: the mean
    // over time is 0.7, over samples 0.62.
    validation::ImpactPressureResult::Sensor uneven;
    uneven.name = "P3";
    for (int k = 0; k <= 1250; ++k) uneven.measured.emplace_back(3.0 + k * 0.001, 0.6);   // 3 .. 4.25, every 0.001
    for (int k = 1; k <= 125; ++k) uneven.measured.emplace_back(4.25 + k * 0.01, 0.8);    // 4.26 .. 5.5, every 0.01
    uneven.simulated = {{0.0, 0.0}, {7.0, 0.0}};
    validation::compare_sensor(uneven, 3.0, 5.5);
    CHECK(uneven.mean_measured == Approx(0.7).margin(0.002));   // the step's sample interval, 0.01 of 2.5, at 0.2
    CHECK(s.mean_simulated > 0.7);   // the shifted descent is still above its plateau at the window's start

    // A reading that never reaches the level has no onset; a simulation short of the window is no measurement.
    validation::ImpactPressureResult::Sensor dry = s;
    for (auto& [t, p] : dry.simulated) p = 0.1;
    validation::compare_sensor(dry, 3.0, 5.5);
    CHECK_FALSE(dry.onset_simulated);
    CHECK(dry.rms_error == Approx(0.5).margin(1e-12));
    validation::ImpactPressureResult::Sensor short_run = s;
    short_run.simulated.resize(500);   // to T = 2.5
    CHECK_THROWS_AS(validation::compare_sensor(short_run, 3.0, 5.5), validation::NoMeasurement);
}

TEST_CASE("impact pressure: the commands' case names choose the two impact cases, another is refused by name",
          "[validation][unit]") {
    CHECK(validation::is_impact_case("impact-pressure"));
    CHECK(validation::is_impact_case("obstacle-impact"));
    for (const char* other : {"dam-break", "hydrostatic", "standing-wave", "impact", ""}) {
        INFO("case '" << other << "'");
        CHECK_FALSE(validation::is_impact_case(other));
        // Refused, as bad input naming the case, before the scene or the shaders are read (no context here).
        const ranryu::scene::Scene scene{};
        const auto shaders = ranryu::shader::FileSource::embedded();
        CHECK_THROWS_AS(validation::impact_case(other, scene, shaders), ranryu::InputError);
        CHECK_THROWS_WITH(validation::impact_case(other, scene, shaders),
                          Catch::Contains("unknown impact case '" + std::string(other) + "'"));
    }
}
