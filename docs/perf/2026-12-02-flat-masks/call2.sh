#!/usr/bin/env bash
# Call 2: the flat loop written as one turn a run change or a visit (flat2b: the accelerate and residual
# passes), against the tree, iteration-bench.sh at 30 iterations.
set -u
[ -x build/gpu/app/ranryu ] || scripts/gpu/setup-and-build.sh ranryu > /tmp/b.txt 2>&1 || { tail -30 /tmp/b.txt; exit 1; }
VARIANTS="current flat2b" scripts/gpu/iteration-bench.sh 2>&1 | grep -E "^==|pressure.solve|divergence.solve"
