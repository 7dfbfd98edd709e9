#!/usr/bin/env bash
# Call 4: issue 11's and 12's table with the tree as committed (the kernel's constants as operands,
# WCSPH's forces pass and PBF's correction as folded sums, the residual pass's reads before its stores):
# the dam break's whole pipeline (water shading at 1920x1080) over frames 20-40, each solver as the
# scene ships it, at 64k-1M (`bench-dfsph.sh`), as call 3 of docs/perf/2026-11-30-h200-warm-impulse/.
set -u
scripts/gpu/setup-and-build.sh ranryu > $OUT/build.txt 2>&1 || { tail -30 $OUT/build.txt; exit 1; }
. scripts/gpu/env.sh x
mkdir -p bench
{ nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; date -u; } | tee bench/device.txt
OUT=$PWD/bench scripts/gpu/bench-dfsph.sh "dfsph wcsph pbf" "0.005 0.004 0.00317 0.0025 0.002" 20 20 2>&1 | tee $OUT/side-by-side.txt
tar czf $OUT/bench.tgz bench
