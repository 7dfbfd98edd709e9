#!/usr/bin/env bash
# Call 5 (the tree of 13fbf25): the dam break for ten seconds with DFSPH's no-slip walls (D7),
# sph.boundary_viscosity 1e-4 at 250k and 1M and 1e-3 at 250k, against call 4's free-slip runs.
set -u
scripts/gpu/setup-and-build.sh ranryu > $OUT/build.txt 2>&1 || { tail -30 $OUT/build.txt; exit 1; }
export RUN_TIMEOUT=200
TAG=noslip NS="250000 1000000" ETAS=1e-3 KEYS="sph.boundary_viscosity=1e-4" scripts/gpu/dfsph-eta.sh 2>&1 | grep -v "why its settings" | tee $OUT/noslip.txt
TAG=noslip3 NS="250000" ETAS=1e-3 KEYS="sph.boundary_viscosity=1e-3" scripts/gpu/dfsph-eta.sh 2>&1 | grep -v "why its settings" | tee $OUT/noslip3.txt
