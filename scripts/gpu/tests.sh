#!/usr/bin/env bash
# On the GPU host, after `scripts/gpu/setup-and-build.sh all`: the three test programs on this device
# (the Release build; the CLI tests skip, each with its reason, what the host lacks: the window, ffmpeg,
# matplotlib, and what its speed or limits make moot; docs/PERFORMANCE.md "A buffer the CPU reads, and
# the GL tests on the H200"). Each program's compact report goes to $OUT (or ./tests-out); prints the
# summaries and every failed assertion. Exit 0 when all three pass.
set -uo pipefail
. "$(dirname "$0")/env.sh" tests-out
out=$(cd "$out" && pwd)
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader
date -u
rc=0
for t in unit gl cli; do
  start=$(date +%s)
  (cd build/gpu/tests && timeout 400 "./ranryu_${t}_tests" -r compact > "$out/$t-tests.txt" 2>&1)
  code=$?
  [ $code -ne 0 ] && rc=1
  echo "== $t tests: rc $code in $(( $(date +%s) - start )) s; $(tail -2 "$out/$t-tests.txt" | head -1)"
  grep -E "failed:" "$out/$t-tests.txt" | cut -c1-400 | head -20
done
exit $rc
