#!/usr/bin/env bash
# What ran, as the script it was then factored into (scripts/gpu/compare-engines.sh): the run itself
# was an inline copy of it with the same profile commands (the 10 s runs under a 120 s timeout, 150 s
# in the script), its output folder named otherwise. It also ran
#     RANRYU_DFSPH_BENCH_SPACING=0.00317 build/gpu/tests/ranryu_gl_tests "[dfsph-bench]"   (bench-merged-0.00317.txt)
#
# on the development machine
#     rm -rf scratch/base && mkdir -p scratch/base && git archive e8882c9 -- . ':!docs/perf' | tar x -C scratch/base
# then on the GPU host, after scripts/gpu/setup-and-build.sh, with the change's tree:
TAG=merged scripts/gpu/compare-engines.sh
