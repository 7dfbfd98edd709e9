#!/usr/bin/env bash
# What an issued, empty iteration's dispatches cost, and how much of it is the driver's work a dispatch:
# bind-cost.patch (a diagnostic, not shipped) reads RANRYU_NO_GROUPS (no debug groups: each solve dispatch
# opens one since the passes within passes) and RANRYU_DOUBLE_BIND (every storage block bound twice before
# each dispatch); the hidden benchmark "[dfsph-bench]" (tests/gl/dfsph_test.cpp) gives an issued
# iteration's cost at 246k from frames issued a lean cap and 100 iterations alternately.
set -u
git apply docs/perf/2026-12-01-h200-passes-within/bind-cost.patch || exit 1
scripts/gpu/setup-and-build.sh ranryu_gl_tests > /tmp/build2.txt 2>&1 || { tail -30 /tmp/build2.txt; exit 1; }
. scripts/gpu/env.sh x
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | tee $OUT/device.txt; date -u | tee -a $OUT/device.txt
for v in as-shipped RANRYU_NO_GROUPS RANRYU_DOUBLE_BIND as-shipped; do
  f=$OUT/bench-$v.txt; [ -e $f ] && f=$OUT/bench-$v-again.txt
  if [ $v = as-shipped ]; then env RANRYU_DFSPH_BENCH_SPACING=0.00317 build/gpu/tests/ranryu_gl_tests "[dfsph-bench]" > $f 2>&1
  else env $v=1 RANRYU_DFSPH_BENCH_SPACING=0.00317 build/gpu/tests/ranryu_gl_tests "[dfsph-bench]" > $f 2>&1; fi
  echo "== $v rc $?"; grep -E "particles|issued iteration" $f
done
