#!/usr/bin/env bash
# Session 32, call 2: (D10) with a targeted safeguard: a particle under pressure whose residual is below
# -eta_peak rho0 (its pressure already expands it past the peak bound) takes the plain Jacobi update.
set -u
scripts/gpu/setup-and-build.sh ranryu > $OUT/build.txt 2>&1 || { tail -30 $OUT/build.txt; exit 1; }
export RUN_TIMEOUT=130
run() { TAG=$1 NS="$2" ETAS=1e-3 SHADERS=$3 KEYS="$4" scripts/gpu/dfsph-eta.sh 2>&1 | grep -v "why its settings" | tee $OUT/$1.txt; }
run overshoot "250000" scratch/glsl-overshoot ""
run dragout-overshoot-05 "250000 1000000" scratch/glsl-dragout-overshoot ""
run dragout-overshoot-075 "250000 1000000" scratch/glsl-dragout-overshoot "sph.dfsph_cfl=0.75"
