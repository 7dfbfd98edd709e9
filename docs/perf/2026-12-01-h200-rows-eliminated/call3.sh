#!/usr/bin/env bash
# sym5, sym6: sym3 and sym4 with the first iteration mended (the prepare pass left the rows at 0 for the
# first residual pass and the divergence solve's kappa_b as the rows' first residual); 0.00625 and
# 0.003125 m, two runs at a time; sym5 at 0.0125 m and the shipped shaders at 0.00625 m.
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
run sym5 0.00625 200 & run sym6 0.00625 200 & wait
run sym5 0.003125 260 & run sym6 0.003125 260 & wait
run sym5 0.0125 120 & run ship 0.00625 200 & wait
for f in $OUT/tank-*.txt; do echo "== $f"; grep -E "^floor layer|interior \(|rms speed averaged|steps in|each half|floor's pair|^rc|unstable" $f; done
