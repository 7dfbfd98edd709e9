#!/usr/bin/env bash
# The tree of ece35ff (the records with fastest_x..z, densest_x..z).
# Call 4: the dam break as shipped for ten seconds at 250k and 1M with the records' new columns: where
# each frame's fastest and densest particles were.
set -u
scripts/gpu/setup-and-build.sh ranryu > $OUT/build.txt 2>&1 || { tail -30 $OUT/build.txt; exit 1; }
export RUN_TIMEOUT=200
TAG=where NS="250000 1000000" ETAS=1e-3 scripts/gpu/dfsph-eta.sh 2>&1 | grep -v "why its settings" | tee $OUT/where.txt
