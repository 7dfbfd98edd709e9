// The DFSPH iteration cap the CPU issues (engine/sim/solvers/dfsph.h next_iteration_cap()): learnt from
// the most one step needed, and the scene's maximum at once after a step stopped at the cap; and the
// CPU's mirror of the step the iterations allow (next_iteration_dt(), docs/DFSPH.md (D8)); and the size of
// the Kappa block the solver allocates (Dfsph::kappa_floats()).
#include <cstdlib>
#include <string>

#include <catch2/catch.hpp>

#include "sim/solvers/dfsph.h"

using ranryu::sim::Dfsph;
using ranryu::sim::iterations_at_plan;
using ranryu::sim::next_iteration_cap;
using ranryu::sim::next_iteration_dt;

TEST_CASE("dfsph iteration cap: 1.5 times the most needed plus two, within the scene's least and most", "[dfsph][unit]") {
    CHECK(next_iteration_cap(3, false, 2, 100) == 7u);     // ceil(4.5) + 2
    CHECK(next_iteration_cap(10, false, 2, 100) == 17u);
    CHECK(next_iteration_cap(0, false, 2, 100) == 2u);     // not below the least
    CHECK(next_iteration_cap(0, false, 5, 100) == 5u);
    CHECK(next_iteration_cap(80, false, 2, 100) == 100u);  // not above the most
    CHECK(next_iteration_cap(4000000000u, false, 2, 1000) == 1000u);
}

TEST_CASE("dfsph iteration cap: another rule, from RANRYU_DFSPH_CAP, with factors that binary fractions hold inexactly", "[dfsph][unit]") {
    using ranryu::sim::IterationCapRule;
    const IterationCapRule tight{1.1, 1.0};
    CHECK(next_iteration_cap(10, false, 2, 100, tight) == 12u);   // ceil(11) + 1, though 1.1 * 10 > 11 in doubles
    CHECK(next_iteration_cap(7, false, 2, 100, tight) == 9u);     // ceil(7.7) + 1
    CHECK(next_iteration_cap(3, false, 2, 100, IterationCapRule{1.0, 0.0}) == 3u);
    CHECK(next_iteration_cap(3, true, 2, 100, tight) == 100u);    // a stop: the most, whatever the rule
    ::unsetenv("RANRYU_DFSPH_CAP");
    CHECK(IterationCapRule::from_environment().factor == 1.5);
    CHECK(IterationCapRule::from_environment().margin == 2.0);
    ::setenv("RANRYU_DFSPH_CAP", "1.25,1", 1);
    CHECK(IterationCapRule::from_environment().factor == 1.25);
    CHECK(IterationCapRule::from_environment().margin == 1.0);
    for (const char* bad : {"1.25", "0.9,1", "1.5,-1", "1.5,30", "1.5,0.5", "1.5,2x", "fast"}) {
        INFO(bad);
        ::setenv("RANRYU_DFSPH_CAP", bad, 1);
        CHECK_THROWS_WITH(IterationCapRule::from_environment(), Catch::Contains(std::string("RANRYU_DFSPH_CAP=") + bad));
    }
    ::unsetenv("RANRYU_DFSPH_CAP");
}

TEST_CASE("dfsph iteration cap: a step stopped at the cap sends it to the scene's most at once", "[dfsph][unit]") {
    // However few iterations the records say a step needed: the stopped step's need is unknown, and a
    // solve cut short leaves its excess to the next step (docs/DFSPH.md "The iteration cap").
    CHECK(next_iteration_cap(3, true, 2, 100) == 100u);
    CHECK(next_iteration_cap(7, true, 2, 60) == 60u);
    CHECK(next_iteration_cap(0, true, 1, 1) == 1u);
}

TEST_CASE("dfsph iteration cap: a record's need scaled to a plan of fewer, longer steps, never down", "[dfsph][unit]") {
    // The dam break's first records at 1M: 59 substeps a frame on the scene's estimate, 4 iterations at
    // most, then a plan of 12 substeps at the records' step: 4 * 59 / 12 = 19.7.
    CHECK(iterations_at_plan(4, 59, 12) == 20u);
    CHECK(next_iteration_cap(iterations_at_plan(4, 59, 12), false, 2, 100) == 32u);   // not 8
    CHECK(iterations_at_plan(10, 12, 12) == 10u);   // the same steps
    CHECK(iterations_at_plan(10, 8, 12) == 10u);    // shorter steps: no fewer
    CHECK(iterations_at_plan(10, 13, 12) == 11u);   // ceil(10.83)
    CHECK(iterations_at_plan(10, 13, 0) == 10u);    // no plan
    CHECK(iterations_at_plan(10, 13, -3) == 10u);
    CHECK(iterations_at_plan(12, 6, 4) == 18u);     // exact: no rounding up
    CHECK(iterations_at_plan(4000000000u, 1000, 1) == 1000000u);   // bounded
}

TEST_CASE("dfsph iteration step: 0.9 times the stable step above the band, 1.1 times below, the same within, clamped", "[dfsph][unit]") {
    // docs/DFSPH.md (D8): the band [grow_below, shrink_above] = [10, 20] of the defaults.
    CHECK(next_iteration_dt(1e-3f, 21, 20, 10, 1e-5f, 5e-3f) == Approx(0.9e-3));
    CHECK(next_iteration_dt(1e-3f, 9, 20, 10, 1e-5f, 5e-3f) == Approx(1.1e-3));
    CHECK(next_iteration_dt(1e-3f, 20, 20, 10, 1e-5f, 5e-3f) == Approx(1e-3));   // the band's ends are in it
    CHECK(next_iteration_dt(1e-3f, 10, 20, 10, 1e-5f, 5e-3f) == Approx(1e-3));
    CHECK(next_iteration_dt(4.9e-3f, 2, 20, 10, 1e-5f, 5e-3f) == 5e-3f);        // not above the largest step
    CHECK(next_iteration_dt(1.05e-5f, 100, 20, 10, 1e-5f, 5e-3f) == 1e-5f);      // nor below the floor
}

TEST_CASE("dfsph kappa block: (x_i, kappa_i) a particle, then the rows' pairs padded to whole vec4s", "[dfsph][unit]") {
    // glsl/sim/dfsph/dfsph.glsl: the vec4 view reads row b's pair from element N + (2b + s) / 4, which
    // must lie inside the buffer for the last row whether the rows are odd or even in number.
    for (const std::size_t count : {std::size_t(1), std::size_t(7), std::size_t(1000)})
        for (const std::size_t rows : {std::size_t(0), std::size_t(1), std::size_t(2), std::size_t(3), std::size_t(2329)}) {
            const std::size_t floats = Dfsph::kappa_floats(count, rows);
            INFO(count << " particles, " << rows << " rows: " << floats << " floats");
            CHECK(floats % 4 == 0);
            CHECK(floats >= 4 * count + 2 * rows);
            CHECK(floats < 4 * count + 2 * rows + 4);
            if (rows > 0) CHECK(count + (2 * (rows - 1) + 1) / 4 < floats / 4);   // the last row's element
        }
    CHECK(Dfsph::kappa_floats(0, 0) == 4);   // one particle's worth when there is none, as the other arrays
}
