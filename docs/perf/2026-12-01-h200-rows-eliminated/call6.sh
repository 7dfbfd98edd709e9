#!/usr/bin/env bash
# sym8: sym7 with every row handing on only its excess, max(r_b, 0) (sym7 hands on the whole residual of a
# row that carries pressure); the tank at rest at 0.00625 and 0.003125 m, settled 1 s, averaged 2 s.
set -u
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
git apply docs/perf/2026-12-01-h200-rows-eliminated/sym7-engine.patch || exit 1
scripts/gpu/setup-and-build.sh ranryu > $OUT/build.txt 2>&1 || { tail -30 $OUT/build.txt; exit 1; }
. scripts/gpu/env.sh x
export RANRYU_PROTO_SYM7=1
run() {   # variant spacing timeout
  timeout $3 $B validate hydrostatic --solver dfsph --spacing $2 --settle 1 --average 2 --quiet \
      --shader-dir $PWD/scratch/$1/glsl > $OUT/tank-$1-$2.txt 2>&1
  echo "rc $?" >> $OUT/tank-$1-$2.txt
}
run sym8 0.003125 150 & run sym8 0.00625 100 & wait
for f in $OUT/tank-*.txt; do echo "== $f"; grep -E "^floor layer|interior \(|rms speed averaged|steps in|each half|floor's pair|^rc|unstable" $f; done
