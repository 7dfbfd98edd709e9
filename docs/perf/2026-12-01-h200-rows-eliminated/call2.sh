#!/usr/bin/env bash
# sym4 (sym3 with a plain step at half the relaxation, no (D10), for particles whose residual holds the
# rows' lagged part) against sym3's blow-up at 0.00625 m in call 1, and the shipped shaders at
# 0.003125 m, two runs at a time (call 1's nine at once starved each other).
set -u
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
git apply docs/perf/2026-11-30-h200-rows-extended/dispatch.patch || exit 1
scripts/gpu/setup-and-build.sh ranryu > $OUT/build.txt 2>&1 || { tail -30 $OUT/build.txt; exit 1; }
. scripts/gpu/env.sh x
run() {   # variant spacing timeout
  timeout $3 $B validate hydrostatic --solver dfsph --spacing $2 --settle 1 --average 2 --quiet \
      --shader-dir $PWD/scratch/$1/glsl > $OUT/tank-$1-$2.txt 2>&1
  echo "rc $?" >> $OUT/tank-$1-$2.txt
}
run sym4 0.00625 200 & run sym3 0.00625 200 & wait
run sym4 0.003125 260 & run ship 0.003125 260 & wait
for f in $OUT/tank-*.txt; do echo "== $f"; grep -E "^floor layer|interior \(|rms speed averaged|steps in|each half|floor's pair|^rc|unstable" $f; done
