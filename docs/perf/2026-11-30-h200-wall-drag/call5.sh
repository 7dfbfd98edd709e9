#!/usr/bin/env bash
# Call 5 (the tree as committed: the drag explicit as before, the iteration cap scaled to a plan of
# longer steps, iterations_at_plan()): the dam break as shipped for ten seconds at 250k and 1M.
set -u
scripts/gpu/setup-and-build.sh ranryu > $OUT/build.txt 2>&1 || { tail -30 $OUT/build.txt; exit 1; }
export RUN_TIMEOUT=150
TAG=cap NS="250000 1000000" ETAS=1e-3 scripts/gpu/dfsph-eta.sh 2>&1 | grep -v "why its settings" | tee $OUT/cap.txt
