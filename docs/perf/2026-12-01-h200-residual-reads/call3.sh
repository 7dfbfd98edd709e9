#!/usr/bin/env bash
# Call 3: the density pass with the step's dt read before its walk (dtfirst) and, with it, the
# viscous sums' 1/rho0 taken out of the visits (dtrcp), against the tree (head): iteration-bench.sh
# (30 iterations a solve, the dfsph.density row) at 246k and 1M, ten seconds at 246k; then the tree
# at 1M with --detail over frames 20-30 (the iteration's two passes apart).
set -u
# The variants: scratch/dtfirst and scratch/dtrcp, copies of glsl/ with variants/dtfirst.patch and
# variants/dtrcp.patch of this folder applied (scratch/base-glsl as for call1.sh).
scripts/gpu/setup-and-build.sh ranryu > /tmp/b.txt 2>&1 || { tail -30 /tmp/b.txt; exit 1; }
. scripts/gpu/env.sh x
VARIANTS="head dtfirst dtrcp" TEN_S_VARIANTS="head dtrcp" timeout 400 scripts/gpu/iteration-bench.sh 2>&1 | grep -E "^==|dfsph.density|dfsph.pressure.solve|fps and|frame \(GPU"
f=$OUT/detail-1m
timeout 100 $B profile --scene dam-break --spacing 0.002 --shading particles --size 640x360 --frames 10 --warmup 20 --detail > $f.txt 2>&1
echo "== detail 1M rc $?"; grep -E "^dfsph|^  dfsph|^ +dfsph|density solve:|fps and" $f.txt
