#!/usr/bin/env bash
# The boundary rows of the density solve extended from the fluid's pressure (scratch/ext/glsl: each
# iteration a row takes the Shepard mean of kappa_j + g·(x_b − x_j)/rho0 over its fluid neighbours, the
# accelerate pass computing it, the residual pass taking it; the divergence solve's rows as before)
# against the shipped shaders, one binary (the accelerate pass dispatched over the rows' workgroups too):
# the dam break ten seconds at about 250k and 1M, the front at a/dx = 40, the tank at 0.00625 / 0.003125 m.
set -u
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
scripts/gpu/setup-and-build.sh ranryu > $OUT/build.txt 2>&1 || { tail -30 $OUT/build.txt; exit 1; }
. scripts/gpu/env.sh x
export RUN_TIMEOUT=150
cp -r glsl /tmp/ship
for v in ext ship; do
  sh=/tmp/ship; [ $v = ext ] && sh=$PWD/scratch/ext/glsl
  TAG=$v SHADERS=$sh NS="250000 1000000" ETAS=1e-3 scripts/gpu/dfsph-eta.sh 2>&1 | grep -v "why its settings" | tee $OUT/$v.txt
  if [ $v = ext ]; then
    python3 scripts/gpu/scene-at.py dam-break /tmp/db.json 1000 > /dev/null
    timeout 100 $B validate dam-break --scene /tmp/db.json --solver dfsph --spacing 0.005 --shader-dir $sh --json $OUT/front-$v.json --quiet > $OUT/front-$v.txt 2>&1
    echo "== front a/dx 40 $v rc $? $(grep -m1 'surge front error' $OUT/front-$v.txt)" | tee -a $OUT/$v.txt
    for dx in 0.00625 0.003125; do
      timeout 120 $B validate hydrostatic --solver dfsph --spacing $dx --settle 1 --average 2 --shader-dir $sh --json $OUT/tank-$v-$dx.json > $OUT/tank-$v-$dx.txt 2>&1
      echo "== tank $dx $v rc $?"; grep -E "^floor layer|interior \(|rms speed|steps in" $OUT/tank-$v-$dx.txt | tee -a $OUT/$v.txt
    done
  fi
done
