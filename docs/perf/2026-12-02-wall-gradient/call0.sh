#!/usr/bin/env bash
# Call 0 (2026-12-02, the session's last device seconds): call1.sh's iteration at 1M alone, head against
# current (wall-gradient.patch applied), every density solve at 30 iterations.
set -u
scripts/gpu/setup-and-build.sh ranryu > /tmp/b.txt 2>&1 || { tail -30 /tmp/b.txt; exit 1; }
. scripts/gpu/env.sh x
COUNTS=1000000 VARIANTS="head current" timeout 150 scripts/gpu/iteration-bench.sh 2>&1 | \
  grep -E "^==|pressure.solve|divergence.solve|dfsph.density|fps and"
