#!/usr/bin/env bash
# Call 8, prepared, not run: the divergence solve's warm start as its impulse (divergence-warm-impulse.patch:
# Warm.y keeps dt·kappa_v, the next step divides by its dt; kappa_v itself scales as 1/dt, (D5), so a
# warm start of the raw kappa_v is off by the ratio of the two steps). Apply the patch to the tree
# first (git apply docs/perf/2026-11-30-h200-wall-drag/divergence-warm-impulse.patch) and run
# make-shaders.sh after it, so that scratch/glsl-dragout carries it too. The dam break as shipped for
# ten seconds at 250k and 1M (the guard, the largest density, fps against call 5), then with the drag
# out of the force condition (do the floor spikes of calls 1-3 follow the warm start?).
set -u
scripts/gpu/setup-and-build.sh ranryu > $OUT/build.txt 2>&1 || { tail -30 $OUT/build.txt; exit 1; }
export RUN_TIMEOUT=150
TAG=impulse NS="250000 1000000" ETAS=1e-3 scripts/gpu/dfsph-eta.sh 2>&1 | grep -v "why its settings" | tee $OUT/impulse.txt
TAG=impulse-dragout NS="250000 1000000" ETAS=1e-3 SHADERS=scratch/glsl-dragout scripts/gpu/dfsph-eta.sh 2>&1 | grep -v "why its settings" | tee $OUT/impulse-dragout.txt
