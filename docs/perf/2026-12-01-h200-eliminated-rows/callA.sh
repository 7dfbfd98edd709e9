#!/usr/bin/env bash
# The tank at rest at about 1M particles for ten seconds, as docs/perf/2026-11-30-h200-tank-1m-ten-seconds/
# ran it (its callA.sh and callB.sh, run as they are on a warm machine after call1.sh), with the rows
# eliminated as the scene now sets them: SECONDS_A=540 bash docs/perf/2026-11-30-h200-tank-1m-ten-seconds/callA.sh,
# then SECONDS_B=... bash .../callB.sh.
