// The progress line's text (engine/frame/progress.h), without GL: what is known, what is not yet,
// and the ETA's clock form.
#include <catch2/catch.hpp>

#include "frame/progress.h"

using ranryu::frame::progress_line;
using ranryu::frame::ProgressFacts;

TEST_CASE("progress line: frame i/N, simulated time, fps, substeps a frame and ETA", "[progress]") {
    ProgressFacts f;
    f.frame = 37;
    f.total = 120;
    f.simulated_seconds = 0.6171;
    f.fps = 12.34;
    f.substeps = 4;
    CHECK(progress_line("ranryu record", f) == "ranryu record: frame 37/120, t 0.617 s, 12.3 fps, 4 substeps/frame, ETA 0:07");
    f.fps = 1234.0;   // whole frames a second past 100
    CHECK(progress_line("x", f) == "x: frame 37/120, t 0.617 s, 1234 fps, 4 substeps/frame, ETA 0:00");
}

TEST_CASE("progress line: what is not known yet reads -, and no ETA without a length", "[progress]") {
    ProgressFacts f;
    f.frame = 1;
    f.total = 10;
    CHECK(progress_line("p", f) == "p: frame 1/10, t - s, - fps, - substeps/frame, ETA -");
    f.total = 0;
    f.fps = 2.0;
    CHECK(progress_line("p", f) == "p: frame 1, t - s, 2.0 fps, - substeps/frame");
}

TEST_CASE("progress line: the ETA in minutes and hours", "[progress]") {
    ProgressFacts f;
    f.frame = 0;
    f.total = 7384;
    f.fps = 2.0;   // 3692 s
    CHECK_THAT(progress_line("p", f), Catch::EndsWith("ETA 1:01:32"));
    f.total = 150;   // 75 s
    CHECK_THAT(progress_line("p", f), Catch::EndsWith("ETA 1:15"));
}
