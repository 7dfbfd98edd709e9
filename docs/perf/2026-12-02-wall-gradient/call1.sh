#!/usr/bin/env bash
# Call 1, prepared 2026-12-02, not run: the residual pass's boundary term from the density pass's wall
# gradient sum (wall-gradient.patch, applied to the tree before the call: `git apply
# docs/perf/2026-12-02-wall-gradient/wall-gradient.patch`; with it the engine passes
# RANRYU_WALL_GRADIENT_AT to the density and residual passes, which the tree's shaders read and the
# shaders of git's HEAD ignore, so `head` against `current` with the one binary isolates the change).
#     mkdir -p scratch/base-glsl && git archive HEAD glsl | tar x -C scratch/base-glsl
# Runs: the iteration at 30 iterations a solve at 246k and 1M, ten seconds of the dam break at 246k with
# both, then ten seconds at 1M with the change (particle shading 640x360; the guard must stay quiet).
set -u
scripts/gpu/setup-and-build.sh ranryu > /tmp/b.txt 2>&1 || { tail -30 /tmp/b.txt; exit 1; }
. scripts/gpu/env.sh x
VARIANTS="head current" TEN_S_VARIANTS="head current" timeout 300 scripts/gpu/iteration-bench.sh 2>&1 | \
  grep -E "^==|pressure.solve|dfsph.integrate|fps and|guard"
SOLVER=dfsph PARTICLES=1000000 SCENES=dam-break RUN_TIMEOUT=200 timeout 230 scripts/gpu/scenes-seconds.sh 10 2>&1 | tail -12
