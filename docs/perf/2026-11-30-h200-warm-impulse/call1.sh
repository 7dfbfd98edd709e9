#!/usr/bin/env bash
# Call 1: the divergence solve's warm start as its impulse (Warm.y keeps dt·kappa_v, the next step
# divides by its own dt: the tree of this call, glsl/ as committed after it). The dam break for ten
# seconds at 250k and 1M as shipped (against call 5 of ../2026-11-30-h200-wall-drag/, the raw kappa_v),
# then with the wall's drag out of (D8)'s force condition at the shipped Courant number 0.5 and at 0.75
# (do the floor layers' spikes of that folder's calls 1 and 3 follow the warm start's step ratio?).
# Before it, in the repository's root: bash docs/perf/2026-11-30-h200-wall-drag/make-shaders.sh
# (scratch/glsl-dragout, from glsl/ with the impulse, and that folder's implicit-drag.patch).
set -u
scripts/gpu/setup-and-build.sh ranryu > $OUT/build.txt 2>&1 || { tail -30 $OUT/build.txt; exit 1; }
export RUN_TIMEOUT=150
TAG=impulse NS="250000 1000000" ETAS=1e-3 scripts/gpu/dfsph-eta.sh 2>&1 | grep -v "why its settings" | tee $OUT/impulse.txt
TAG=impulse-dragout NS="250000 1000000" ETAS=1e-3 SHADERS=scratch/glsl-dragout scripts/gpu/dfsph-eta.sh 2>&1 | grep -v "why its settings" | tee $OUT/impulse-dragout.txt
TAG=impulse-dragout-cfl075 NS="250000 1000000" ETAS=1e-3 SHADERS=scratch/glsl-dragout KEYS="sph.dfsph_cfl=0.75" scripts/gpu/dfsph-eta.sh 2>&1 | grep -v "why its settings" | tee $OUT/impulse-dragout-cfl075.txt
