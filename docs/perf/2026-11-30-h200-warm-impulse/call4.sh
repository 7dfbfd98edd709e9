#!/usr/bin/env bash
# Call 4: the bundled scenes other than the dam break with --solver dfsph after the divergence warm
# start's impulse and the tank's 4 ms step cap (the tree of this folder's llvmpipe/ commit): ten seconds
# at about 250k (drop, jet, tank at rest) and 1M (drop, jet) particles, the guard watching
# (`scenes-seconds.sh`); the tank at rest at 1M for four seconds (its ten take some 5 minutes, more than
# the call had left). The dam break's ten seconds are call 1's.
set -u
scripts/gpu/setup-and-build.sh ranryu > $OUT/build.txt 2>&1 || { tail -30 $OUT/build.txt; exit 1; }
mkdir -p seconds/250k seconds/1m seconds/tank-1m
OUT=$PWD/seconds/250k SOLVER=dfsph PARTICLES=250000 SCENES="drop turbulent-jet hydrostatic" scripts/gpu/scenes-seconds.sh 10 2>&1 | tee $OUT/seconds.txt
OUT=$PWD/seconds/1m SOLVER=dfsph PARTICLES=1000000 SCENES="drop turbulent-jet" scripts/gpu/scenes-seconds.sh 10 2>&1 | tee -a $OUT/seconds.txt
OUT=$PWD/seconds/tank-1m SOLVER=dfsph PARTICLES=1000000 SCENES="hydrostatic" scripts/gpu/scenes-seconds.sh 4 2>&1 | tee -a $OUT/seconds.txt
tar czf $OUT/seconds.tgz seconds
