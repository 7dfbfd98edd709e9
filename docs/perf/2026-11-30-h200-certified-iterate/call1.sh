#!/usr/bin/env bash
# Session 33, call 1: the density solve's certified iterate applied (the integration takes a^p of the
# kappa whose residual the last iteration measured, from PressureAccel, without a walk) instead of (D10)'s
# last, unmeasured extrapolation. Do the floor spikes of the drag out go with it?
set -u
scripts/gpu/setup-and-build.sh ranryu > $OUT/build.txt 2>&1 || { tail -30 $OUT/build.txt; exit 1; }
export RUN_TIMEOUT=130
run() { TAG=$1 NS="$2" ETAS=1e-3 SHADERS=$3 KEYS="$4" scripts/gpu/dfsph-eta.sh 2>&1 | grep -v "why its settings" | tee $OUT/$1.txt; }
run cert "250000" scratch/glsl-cert ""
run dragout-cert "250000" scratch/glsl-dragout-cert ""
run dragout-cert-prev "250000" scratch/glsl-dragout-cert-prev ""
run dragout-cert-1m "1000000" scratch/glsl-dragout-cert ""
run cert-1m "1000000" scratch/glsl-cert ""
