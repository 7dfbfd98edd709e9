#!/usr/bin/env bash
# Call 1 (2026-12-02, evening): the walks' masks in one loop over the runs (RANRYU_FLAT_MASKS,
# glsl/sim/fluid/neighbours.glsl), after the replica on the dam break's own particles found it 19 % faster
# there (docs/perf/2026-12-02-replica-real-state/). Variants (scratch/NAME/glsl, made on the development
# machine): head (git's HEAD), current (the tree: the function, no pass using it), flat2 (the density
# solve's accelerate and residual passes), flat5 (and the divergence finish, the prediction, the
# integration). iteration-bench.sh at 30 iterations a solve, then each variant's ten seconds at 246k.
set -u
scripts/gpu/setup-and-build.sh ranryu > /tmp/b.txt 2>&1 || { tail -30 /tmp/b.txt; exit 1; }
BASE_GLSL=scratch/base-glsl VARIANTS="head current flat2 flat5" TEN_S_VARIANTS="current flat2 flat5" \
  scripts/gpu/iteration-bench.sh 2>&1 | grep -v "^why its settings"
