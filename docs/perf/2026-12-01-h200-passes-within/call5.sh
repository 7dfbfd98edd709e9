#!/usr/bin/env bash
# A lead from call 4's detail: at 1M the density solve's residual pass costs 0.31 ms a run iteration against
# the accelerate pass's 0.19, where their walks cost about the same. The residual pass reads its SolveState
# (iteration, solve, Chebyshev weight) and step.dt from blocks declared `coherent`, which NVIDIA serves past
# L1: some 5 loads of one address an invocation. Variants (copies of glsl/ with one word changed, made on the
# development machine: `nocoh` the residual pass's Solve block not coherent, `nocoh2` also the fluid's Step
# block, shared by every pass). What they change is where the loads are served, not what they read (the
# fields are written by earlier dispatches, behind their barriers), so the ten-second records must be equal.
set -u
scripts/gpu/setup-and-build.sh ranryu > /tmp/build5.txt 2>&1 || { tail -30 /tmp/build5.txt; exit 1; }
. scripts/gpu/env.sh x
VARIANTS="current nocoh nocoh2" TEN_S_VARIANTS="current nocoh nocoh2" COUNTS="246078 1000000" scripts/gpu/iteration-bench.sh 2>&1 \
  | grep -E "^== |dfsph\.pressure\.solve|dfsph\.divergence\.solve|^frame|fps and|density solve"
tar xzf $OUT/bench.tgz -C /tmp
for v in nocoh nocoh2; do cmp -s /tmp/bench/db10-current.csv /tmp/bench/db10-$v.csv && echo "records $v: equal to current's" || echo "records $v: differ"; done
