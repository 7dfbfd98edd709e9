#!/usr/bin/env bash
# Call 3 (2026-12-02): kappa_j fetched with x_j (one 16-byte load a neighbour in the accelerate pass, the
# residual pass storing (x_i, kappa_i) after the rows' kappa in the Kappa buffer: engine-pk.patch,
# variants/pk.patch), the nine (start, mask) pairs loaded before the walk (variants/preload.patch, in
# neighbours.glsl: every masked walk), and both (variants/pkpre.patch). Runs: iteration-bench.sh at 246k and
# 1M, ten seconds at 246k, WCSPH at 246k with head and preload (its forces pass walks the masks too).
set -u
scripts/gpu/setup-and-build.sh ranryu > /tmp/b.txt 2>&1 || { tail -30 /tmp/b.txt; exit 1; }
. scripts/gpu/env.sh x
VARIANTS="head pk preload pkpre" TEN_S_VARIANTS="head pk preload pkpre" WCSPH_VARIANTS="head preload" \
  timeout 500 scripts/gpu/iteration-bench.sh 2>&1 | tail -100
