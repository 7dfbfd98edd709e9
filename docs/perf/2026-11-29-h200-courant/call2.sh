#!/usr/bin/env bash
# Session 22, call 2: the Courant number 0.5 and 0.6 with the shipped bounds; the front at a/dx = 40.
cd "$(dirname "$0")/.."
scripts/gpu/setup-and-build.sh ranryu > $OUT/build.txt 2>&1 || { tail -30 $OUT/build.txt; exit 1; }
tail -1 $OUT/build.txt
R=$OUT/r; mkdir -p $R
TAG=cfl5 KEYS="sph.cfl=0.5" ETAS=1e-3 NS="1000000" FRONT_ETAS=1e-3 OUT=$R scripts/gpu/dfsph-eta.sh 2>&1 | grep -v "why its" > $R/cfl5.txt; cat $R/cfl5.txt
TAG=cfl6 KEYS="sph.cfl=0.6" ETAS=1e-3 NS="250000 1000000" FRONT_ETAS=1e-3 OUT=$R scripts/gpu/dfsph-eta.sh 2>&1 | grep -v "why its" > $R/cfl6.txt; cat $R/cfl6.txt
tar czf $OUT/call2.tgz -C $OUT r && rm -rf $R
