#!/usr/bin/env bash
# A lead on the density solve's residual pass (glsl/sim/dfsph/correct_pressure.comp), whose run costs about
# 0.12 ms more than the accelerate pass's at 1M ("Passes within passes, timed apart"): its workgroup's error
# and peak are reduced by a tree in shared memory, seven levels of barriers. Two variants, written by the
# development machine under the untracked scratch/ (not kept; `call3/*.patch` are their diffs against
# glsl/): `noreduce` leaves the reduction out (a diagnostic: the solve then stops at its cap, which the
# bench fixes at 30 iterations anyway), `sharedsum` sums the workgroup's errors in fixed point (2^-24 a
# unit) by shared atomics and takes the peak by a shared atomicMax, two barriers. Each against the tree
# (`current`) with scripts/gpu/iteration-bench.sh (30 iterations a solve, about 246k and 1M particles),
# and `sharedsum` for the dam break's ten seconds at 250k against `current`.
set -u
scripts/gpu/setup-and-build.sh ranryu > /tmp/build3.txt 2>&1 || { tail -30 /tmp/build3.txt; exit 1; }
VARIANTS="current noreduce sharedsum current" TEN_S_VARIANTS="current sharedsum" bash scripts/gpu/iteration-bench.sh 2>&1 \
  | grep -E "^==|dfsph\.pressure\.solve|frame \(GPU|density solve|fps and"
. scripts/gpu/env.sh x
python3 scripts/gpu/compare-records.py <(tar xzf $OUT/bench.tgz -O bench/db10-sharedsum.csv) <(tar xzf $OUT/bench.tgz -O bench/db10-current.csv)
