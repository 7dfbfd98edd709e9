#!/usr/bin/env bash
# Session 32, call 3: which part of the adaptive restart removes the floor's spikes with the drag out of
# (D8)'s force condition (Courant number 0.5): the rows only, the fluid only, the fluid where |r_i| > eta rho0.
set -u
scripts/gpu/setup-and-build.sh ranryu > $OUT/build.txt 2>&1 || { tail -30 $OUT/build.txt; exit 1; }
export RUN_TIMEOUT=125
run() { TAG=$1 NS="$2" ETAS=1e-3 SHADERS=$3 KEYS="$4" scripts/gpu/dfsph-eta.sh 2>&1 | grep -v "why its settings" | tee $OUT/$1.txt; }
run rows-restart "250000" scratch/glsl-rows-restart ""
run fluid-restart "250000" scratch/glsl-fluid-restart ""
run big-restart "250000" scratch/glsl-big-restart ""
run rows-restart-1m "1000000" scratch/glsl-rows-restart ""
run big-restart-1m "1000000" scratch/glsl-big-restart ""
