#!/usr/bin/env bash
# On the development machine:
#     rm -rf scratch/base && mkdir -p scratch/base && git archive 6f5b0bb -- . ':!docs/perf' | tar x -C scratch/base
# then on the GPU host, after scripts/gpu/setup-and-build.sh, with the change's tree:
SPACINGS="0.005 0.00317" TAG=barrier scripts/gpu/compare-engines.sh
. scripts/gpu/env.sh x
RANRYU_DFSPH_BENCH_SPACING=0.00317 build/gpu/tests/ranryu_gl_tests "[dfsph-bench]" | tee "$OUT/bench-barrier.txt"
