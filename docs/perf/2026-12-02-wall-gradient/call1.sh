#!/usr/bin/env bash
# Call 1 (run 2026-12-02, a session later than the patch): the wall-gradient patch applied to the tree
# (`git apply wall-gradient.patch`; with it the engine passes RANRYU_WALL_GRADIENT_AT to the density and
# residual passes, which the tree's shaders read and the shaders of git's HEAD ignore, so `head` against
# `current` with the one binary isolates the change), before it lands:
#     mkdir -p scratch/base-glsl && git archive HEAD glsl | tar x -C scratch/base-glsl
# 1. the iteration at 30 iterations a solve at 246k and 1M, head against current, and ten seconds of the
#    dam break at 246k with both (iteration-bench.sh);
# 2. ten seconds of the dam break at 1M with the change, the guard watching;
# 3. the drop's and the jet's ten seconds with --solver dfsph at about 250k and 1M with the change.
set -u
scripts/gpu/setup-and-build.sh ranryu > /tmp/b.txt 2>&1 || { tail -30 /tmp/b.txt; exit 1; }
. scripts/gpu/env.sh x
root=$OUT
VARIANTS="head current" TEN_S_VARIANTS="head current" timeout 200 scripts/gpu/iteration-bench.sh 2>&1 | \
  grep -E "^==|pressure.solve|divergence.solve|dfsph.density|dfsph.integrate|fps and|guard"
OUT=$root/db-1m SOLVER=dfsph PARTICLES=1000000 SCENES=dam-break RUN_TIMEOUT=130 timeout 140 scripts/gpu/scenes-seconds.sh 10 2>&1 | tail -4
(cd "$root" && tar czf db-1m.tgz db-1m && rm -rf db-1m)
OUT=$root/scenes-250k SOLVER=dfsph PARTICLES=250000 SCENES="drop turbulent-jet" RUN_TIMEOUT=40 timeout 90 scripts/gpu/scenes-seconds.sh 10 2>&1 | tail -6
(cd "$root" && tar czf scenes-250k.tgz scenes-250k && rm -rf scenes-250k)
OUT=$root/scenes-1m SOLVER=dfsph PARTICLES=1000000 SCENES="drop turbulent-jet" RUN_TIMEOUT=100 timeout 205 scripts/gpu/scenes-seconds.sh 10 2>&1 | tail -6
(cd "$root" && tar czf scenes-1m.tgz scenes-1m && rm -rf scenes-1m)
ls -la "$root"
