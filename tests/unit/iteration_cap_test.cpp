// The DFSPH iteration cap the CPU issues (engine/sim/solvers/dfsph.h next_iteration_cap()): learnt from
// the most one step needed, and the scene's maximum at once after a step stopped at the cap.
#include <catch2/catch.hpp>

#include "sim/solvers/dfsph.h"

using ranryu::sim::next_iteration_cap;

TEST_CASE("dfsph iteration cap: 1.5 times the most needed plus two, within the scene's least and most", "[dfsph][unit]") {
    CHECK(next_iteration_cap(3, false, 2, 100) == 7u);     // ceil(4.5) + 2
    CHECK(next_iteration_cap(10, false, 2, 100) == 17u);
    CHECK(next_iteration_cap(0, false, 2, 100) == 2u);     // not below the least
    CHECK(next_iteration_cap(0, false, 5, 100) == 5u);
    CHECK(next_iteration_cap(80, false, 2, 100) == 100u);  // not above the most
    CHECK(next_iteration_cap(4000000000u, false, 2, 1000) == 1000u);
}

TEST_CASE("dfsph iteration cap: a step stopped at the cap sends it to the scene's most at once", "[dfsph][unit]") {
    // However few iterations the records say a step needed: the stopped step's need is unknown, and a
    // solve cut short leaves its excess to the next step (docs/DFSPH.md "The iteration cap").
    CHECK(next_iteration_cap(3, true, 2, 100) == 100u);
    CHECK(next_iteration_cap(7, true, 2, 60) == 60u);
    CHECK(next_iteration_cap(0, true, 1, 1) == 1u);
}
