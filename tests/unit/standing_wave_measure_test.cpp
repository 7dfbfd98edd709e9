// The standing wave's measurement (engine/validation/cases.h, measure_mode): the period and decay
// read from a moment series, on synthetic series whose answers are known in closed form.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include "validation/cases.h"

namespace validation = ranryu::validation;

namespace {
// m(t) = c + a·e^(−λt)·cos(2πt/T), sampled every dt for `periods` periods.
validation::StandingWaveResult series(double T, double lambda, double dt, double periods, double theory) {
    validation::StandingWaveResult r;
    r.period_theory = theory;
    for (double t = 0.0; t <= periods * T + 1e-12; t += dt)
        r.moment.emplace_back(t, 0.05 + 0.01 * std::exp(-lambda * t) * std::cos(2.0 * std::numbers::pi * t / T));
    return r;
}
}  // namespace

TEST_CASE("standing wave: the period and decay of a sampled damped cosine", "[validation][unit]") {
    // Sampled at the frame rate (60 Hz) for three periods, as the case does. The crossings are linear
    // between samples: the cosine's curvature at a crossing is zero, so each is placed to
    // O((ω dt)³) ≈ 2e-4 of a sample; the mean of an undamped cosine over whole periods is c to the
    // sampling (1/N) — the period to 0.1 %. With damping the mean shifts by the decay's residue and
    // the crossings follow it: asserted to 1 %. The decay from the first and last half-period swings
    // is exact for e^(−λt) up to where the swings' peaks fall between samples (cos of half a
    // sample, 0.3 % at T = 0.9 s): λ to 3 %.
    const double T = 0.884, dt = 1.0 / 60.0;
    validation::StandingWaveResult r = series(T, 0.0, dt, 3.0, 0.9);
    validation::measure_mode(r);
    CHECK(r.half_periods >= 4);
    CHECK(r.period == Approx(T).epsilon(1e-3));
    CHECK(std::abs(r.period_error - std::abs(T - 0.9) / 0.9) < 1e-3);   // the period's 0.1 %, over T_theory
    CHECK(std::abs(r.decay_rate) < 0.02);

    r = series(T, 0.5, dt, 3.0, T);
    validation::measure_mode(r);
    CHECK(r.period == Approx(T).epsilon(1e-2));
    CHECK(r.decay_rate == Approx(0.5).epsilon(0.03));
}

TEST_CASE("standing wave: a surface that does not oscillate is no measurement", "[validation][unit]") {
    // Over-damped: the moment relaxes monotonically, crossing its own mean once.
    validation::StandingWaveResult r;
    r.period_theory = 0.884;
    for (int f = 0; f <= 160; ++f) {
        const double t = f / 60.0;
        r.moment.emplace_back(t, 0.01 * std::exp(-3.0 * t));
    }
    CHECK_THROWS_AS(validation::measure_mode(r), validation::NoMeasurement);
    // A constant moment: no crossing at all.
    r.moment.assign(100, {0.0, 0.05});
    for (int f = 0; f < 100; ++f) r.moment[std::size_t(f)].first = f / 60.0;
    CHECK_THROWS_AS(validation::measure_mode(r), validation::NoMeasurement);
}
