#!/usr/bin/env bash
# Session 32, call 1: (D10) with an adaptive restart (a particle whose momentum opposes its Jacobi
# update takes the plain update), as shipped and with the wall's drag out of (D8)'s force condition.
set -u
scripts/gpu/setup-and-build.sh ranryu > $OUT/build.txt 2>&1 || { tail -30 $OUT/build.txt; exit 1; }
export RUN_TIMEOUT=140
run() { TAG=$1 NS="$2" ETAS=1e-3 SHADERS=$3 KEYS="$4" scripts/gpu/dfsph-eta.sh 2>&1 | grep -v "why its settings" | tee $OUT/$1.txt; }
run base "250000" glsl ""
run restart "250000 1000000" scratch/glsl-restart ""
run dragout-restart-075 "250000 1000000" scratch/glsl-dragout-restart "sph.dfsph_cfl=0.75"
run dragout-restart-05 "250000 1000000" scratch/glsl-dragout-restart ""
