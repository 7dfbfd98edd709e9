#!/usr/bin/env bash
# What ran, as the script it was then factored into (scripts/gpu/compare-engines.sh): the run itself
# was an inline copy of it with the same profile commands (the 10 s runs under a 120 s timeout, 150 s
# in the script), its output folder named otherwise.
#
# on the development machine
#     rm -rf scratch/base && mkdir -p scratch/base && git archive b18ee5e -- . ':!docs/perf' | tar x -C scratch/base
# then on the GPU host, after scripts/gpu/setup-and-build.sh, with the change's tree:
TAG=listed scripts/gpu/compare-engines.sh
