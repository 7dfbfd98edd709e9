#!/usr/bin/env bash
# Session 22, call 1: side-by-side DFSPH with the shipped bounds; eta 2e-3; cfl 0.5; no divergence solve.
cd "$(dirname "$0")/.."
scripts/gpu/setup-and-build.sh ranryu > $OUT/build.txt 2>&1 || { tail -30 $OUT/build.txt; exit 1; }
tail -2 $OUT/build.txt
R=$OUT/r; mkdir -p $R
OUT=$R/side scripts/gpu/bench-dfsph.sh "dfsph" "0.005 0.004 0.00317 0.0025 0.002" 20 20 > $R/side.txt 2>&1
tail -8 $R/side.txt
TAG=eta2 ETAS=2e-3 NS="250000 1000000" OUT=$R scripts/gpu/dfsph-eta.sh > $R/eta2.txt 2>&1; cat $R/eta2.txt
TAG=cfl5 KEYS="sph.cfl=0.5" ETAS=1e-3 NS="250000" OUT=$R scripts/gpu/dfsph-eta.sh > $R/cfl5.txt 2>&1; cat $R/cfl5.txt
TAG=nodiv KEYS="sph.divergence_solve=false" ETAS=1e-3 NS="250000" OUT=$R scripts/gpu/dfsph-eta.sh > $R/nodiv.txt 2>&1; cat $R/nodiv.txt
tar czf $OUT/call1.tgz -C $OUT r && rm -rf $R
