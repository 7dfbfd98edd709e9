#!/usr/bin/env bash
# Call 2 (the tree of call 1): what the settled pool's density spikes of call 1 follow. The dam break
# for ten seconds at 250k and 1M (a) with the drag explicit and out of the force condition, bounded by
# the explicit drag's stability step 0.07 h^2/nu_b as sph.max_time_step (2.85 ms at 250k, 1.12 ms at
# 1M; scratch/glsl-explicit of make-shaders.sh, run as scratch/v1/glsl), (b) as call 1
# with (D8)'s iteration band's top at 15 (sph.shrink_step_above) in place of 20.
set -u
scripts/gpu/setup-and-build.sh ranryu > $OUT/build.txt 2>&1 || { tail -30 $OUT/build.txt; exit 1; }
export RUN_TIMEOUT=150
TAG=explicit-250k NS="250000" ETAS=1e-3 SHADERS=scratch/glsl-explicit KEYS="sph.max_time_step=0.00285" scripts/gpu/dfsph-eta.sh 2>&1 | grep -v "why its settings" | tee $OUT/explicit.txt
TAG=explicit-1m NS="1000000" ETAS=1e-3 SHADERS=scratch/glsl-explicit KEYS="sph.max_time_step=0.00112" scripts/gpu/dfsph-eta.sh 2>&1 | grep -v "why its settings" | tee -a $OUT/explicit.txt
TAG=band15 NS="250000 1000000" ETAS=1e-3 KEYS="sph.shrink_step_above=15" scripts/gpu/dfsph-eta.sh 2>&1 | grep -v "why its settings" | tee $OUT/band15.txt
