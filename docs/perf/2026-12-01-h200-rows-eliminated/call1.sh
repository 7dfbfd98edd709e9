#!/usr/bin/env bash
# The rows eliminated into the fluid's equations (sym2: the rows' extension E_b with the rows' residuals
# handed to their fluid neighbours theta-weighted; sym3: the same, the hydrostatic offset only from fluid
# that carries pressure), against the shipped shaders: the tank at rest at 0.0125, 0.00625 and 0.003125 m,
# settled 1 s and averaged 2 s (the binary with dispatch.patch, whose rows' workgroups return at once in
# the shipped shaders).
set -u
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
git apply docs/perf/2026-11-30-h200-rows-extended/dispatch.patch || exit 1
scripts/gpu/setup-and-build.sh ranryu > $OUT/build.txt 2>&1 || { tail -30 $OUT/build.txt; exit 1; }
. scripts/gpu/env.sh x
for v in ship sym2 sym3; do
  for dx in 0.0125 0.00625 0.003125; do
    ( timeout 400 $B validate hydrostatic --solver dfsph --spacing $dx --settle 1 --average 2 --quiet \
        --shader-dir $PWD/scratch/$v/glsl --json $OUT/tank-$v-$dx.json > $OUT/tank-$v-$dx.txt 2>&1
      echo "rc $?" >> $OUT/tank-$v-$dx.txt ) &
  done
done
wait
for v in ship sym2 sym3; do for dx in 0.0125 0.00625 0.003125; do
  echo "== $v $dx"; grep -E "^floor layer|interior \(|rms speed averaged|steps in|each half|floor's pair|^rc" $OUT/tank-$v-$dx.txt
done; done
