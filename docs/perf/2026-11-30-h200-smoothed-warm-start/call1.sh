#!/usr/bin/env bash
# Call 1: the density solve's warm start Shepard-smoothed (b1w1: beta 1, the rows' kappa_b included;
# b05w1: beta 0.5) against the shaders as committed: the dam break ten seconds at 250k and 1M, then
# the tank at rest at 0.00625 and 0.003125 m averaged over 2 s.
set -u
scripts/gpu/setup-and-build.sh ranryu > $OUT/build.txt 2>&1 || { tail -30 $OUT/build.txt; exit 1; }
. scripts/gpu/env.sh x
export RUN_TIMEOUT=150
for v in base b1w1; do
  TAG=$v NS="250000 1000000" ETAS=1e-3 SHADERS=scratch/smooth/$v scripts/gpu/dfsph-eta.sh 2>&1 | grep -v "why its settings" | tee $OUT/db-$v.txt
done
TAG=b05w1 NS="250000" ETAS=1e-3 SHADERS=scratch/smooth/b05w1 scripts/gpu/dfsph-eta.sh 2>&1 | grep -v "why its settings" | tee $OUT/db-b05w1.txt
mkdir -p tank
for dx in 0.00625 0.003125; do for v in base b1w1; do
  s=$(date +%s)
  timeout 100 $B validate hydrostatic --solver dfsph --spacing $dx --average 2 --shader-dir scratch/smooth/$v --json tank/$v-$dx.json --quiet > tank/$v-$dx.txt 2>&1
  echo "== tank $v $dx rc $? $(( $(date +%s) - s )) s"; tail -6 tank/$v-$dx.txt
done; done 2>&1 | tee $OUT/tank.txt
tar czf $OUT/tank.tgz tank
