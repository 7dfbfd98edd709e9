#!/usr/bin/env bash
# Call 7: do the floor spikes follow the Chebyshev acceleration? The dam break at 246k for ten seconds
# with the drag out of the force condition (call 3's tree: HEAD with scratch/glsl-dragout; run
# make-shaders.sh first) at Courant number 0.75, rho_c 0.98 and 0. Prepared, not run: the session's
# device time was spent.
set -u
scripts/gpu/setup-and-build.sh ranryu > $OUT/build.txt 2>&1 || { tail -30 $OUT/build.txt; exit 1; }
export RUN_TIMEOUT=60
for c in 0 0.98; do
  TAG=cheb$c NS="250000" ETAS=1e-3 SHADERS=scratch/glsl-dragout KEYS="sph.dfsph_cfl=0.75 sph.chebyshev=$c" scripts/gpu/dfsph-eta.sh 2>&1 | grep -v "why its settings" | tee $OUT/cheb$c.txt
done
