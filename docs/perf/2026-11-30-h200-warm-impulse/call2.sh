#!/usr/bin/env bash
# Call 2: do the floor layers' spikes at longer steps follow (D10)'s Chebyshev acceleration? The tree of
# call 1 with the wall's drag out of (D8)'s force condition at Courant number 0.75 (call 1's
# impulse-dragout-cfl075 runs, rho_c 0.98 as shipped: 1.550 and 1.429 rho0 at 246k and 1M), here at
# rho_c 0 (plain relaxed Jacobi) and 0.95, ten seconds at 250k and 1M. Before it, in the repository's
# root: bash docs/perf/2026-11-30-h200-wall-drag/make-shaders.sh (scratch/glsl-dragout).
set -u
scripts/gpu/setup-and-build.sh ranryu > $OUT/build.txt 2>&1 || { tail -30 $OUT/build.txt; exit 1; }
export RUN_TIMEOUT=140
for c in 0 0.95; do
  TAG=cheb$c NS="250000 1000000" ETAS=1e-3 SHADERS=scratch/glsl-dragout KEYS="sph.dfsph_cfl=0.75 sph.chebyshev=$c" scripts/gpu/dfsph-eta.sh 2>&1 | grep -v "why its settings" | tee $OUT/cheb$c.txt
done
