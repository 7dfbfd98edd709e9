#!/usr/bin/env bash
# Call 3: a compact-Laplacian blend in the density solve's residual (a Rhie-Chow-like stabilisation of
# the layers' alternation; scratch/rc/gNN: gamma 0.05 and 0.25, the Jacobi diagonal blended alike):
# the tank at rest at 0.0125, 0.00625 and 0.003125 m after 1 and 2 s (gamma 0.25: 1 s), averaged over 2 s (the shipped
# shaders' runs are call 2's), and the dam break ten seconds at 250k with gamma 0.05 (its cost).
set -u
scripts/gpu/setup-and-build.sh ranryu > $OUT/build.txt 2>&1 || { tail -30 $OUT/build.txt; exit 1; }
. scripts/gpu/env.sh x
mkdir -p tankrc
for v in g05 g25; do for settle in 1 2; do for dx in 0.0125 0.00625 0.003125; do
  [ $v = g25 ] && [ $settle = 2 ] && continue
  s=$(date +%s)
  timeout 90 $B validate hydrostatic --solver dfsph --spacing $dx --settle $settle --average 2 --shader-dir scratch/rc/$v --json tankrc/$v-s$settle-$dx.json --quiet > tankrc/$v-s$settle-$dx.txt 2>&1
  f=tankrc/$v-s$settle-$dx.txt
  echo "== $v settle $settle dx $dx rc $? $(( $(date +%s) - s )) s: $(grep -o 'interior (a kernel support from floor and surface): max [0-9.]*' $f | awk '{print $NF}') / $(grep -o 'floor layer: [0-9.]*' $f | awk '{print $NF}'), pair $(grep -o "floor's pair (the floor layer and the next): [0-9.]*" $f | awk '{print $NF}'), rms $(grep -o 'rms speed averaged over the 2 s: [0-9.]*' $f | awk '{print $NF}'), $(tail -1 $f)"
done; done; done 2>&1 | tee $OUT/tankrc.txt
tar czf $OUT/tankrc.tgz tankrc
export RUN_TIMEOUT=60
TAG=g05 NS="250000" ETAS=1e-3 SHADERS=scratch/rc/g05 scripts/gpu/dfsph-eta.sh 2>&1 | grep -v "why its settings" | tee $OUT/db-g05.txt
