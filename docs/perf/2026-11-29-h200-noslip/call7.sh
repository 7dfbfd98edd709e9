#!/usr/bin/env bash
# Prepared, not run: the session's device time was spent (docs/PERFORMANCE.md "The dam break's no-slip walls", its last lead). scratch/visc/glsl is glsl/ with visc.patch applied.
# Call 7 (the tree of 450f67c, the no-slip walls shipped): DFSPH's force condition on gravity alone, the
# viscous terms out of |a|_max (visc.patch), the dam break for ten seconds at 250k and 1M.
set -u
scripts/gpu/setup-and-build.sh ranryu > $OUT/build.txt 2>&1 || { tail -30 $OUT/build.txt; exit 1; }
export RUN_TIMEOUT=150
TAG=visc NS="250000 1000000" ETAS=1e-3 SHADERS=scratch/visc/glsl scripts/gpu/dfsph-eta.sh 2>&1 | grep -v "why its settings" | tee $OUT/visc.txt
