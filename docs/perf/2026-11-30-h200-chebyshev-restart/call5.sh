#!/usr/bin/env bash
# Session 32, call 5: the adaptive restart only within 5 spacings of the tank's floor and side walls
# (and on the rows), with the wall's drag out of (D8)'s force condition, Courant number 0.5.
set -u
scripts/gpu/setup-and-build.sh ranryu > $OUT/build.txt 2>&1 || { tail -30 $OUT/build.txt; exit 1; }
export RUN_TIMEOUT=105
TAG=wall-restart NS="250000 1000000" ETAS=1e-3 SHADERS=scratch/glsl-wall-restart KEYS="" scripts/gpu/dfsph-eta.sh 2>&1 | grep -v "why its settings" | tee $OUT/wall-restart.txt
