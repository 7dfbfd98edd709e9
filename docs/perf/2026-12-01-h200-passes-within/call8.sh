#!/usr/bin/env bash
# Issue 11's table's DFSPH rows with the tree as it ends the day (the residual pass's block not coherent):
# the dam break over the surge (frames 20-40), the whole pipeline at 1920x1080, at 246k and 1M.
set -u
scripts/gpu/setup-and-build.sh ranryu > /tmp/build8.txt 2>&1 || { tail -30 /tmp/build8.txt; exit 1; }
. scripts/gpu/env.sh x
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | tee $OUT/device.txt; date -u | tee -a $OUT/device.txt
scripts/gpu/bench-dfsph.sh "dfsph" "0.00317 0.002" 20 20 2>&1 | tail -8
