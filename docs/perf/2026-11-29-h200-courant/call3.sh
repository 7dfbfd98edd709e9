#!/usr/bin/env bash
# Session 22, call 3: the dam break as shipped with dfsph_cfl 0.5: the surge side by side, a second
# trajectory near 1M for ten seconds, and the front at a/dx = 80.
cd "$(dirname "$0")/.."
scripts/gpu/setup-and-build.sh ranryu > $OUT/build.txt 2>&1 || { tail -30 $OUT/build.txt; exit 1; }
tail -1 $OUT/build.txt
. scripts/gpu/env.sh x
R=$OUT/r; mkdir -p $R
OUT=$R/side scripts/gpu/bench-dfsph.sh "dfsph" "0.005 0.004 0.00317 0.0025 0.002" 20 20 > $R/side.txt 2>&1
tail -7 $R/side.txt
timeout 200 $B validate dam-break --solver dfsph --spacing 0.0025 --json $R/front80.json --quiet > $R/front80.txt 2>&1
echo "front a/dx 80: rc $? $(grep -m1 'surge front error' $R/front80.txt)"
TAG=traj2 ETAS=1e-3 NS="990000" OUT=$R scripts/gpu/dfsph-eta.sh 2>&1 | grep -v "why its" > $R/traj2.txt; cat $R/traj2.txt
tar czf $OUT/call3.tgz -C $OUT r && rm -rf $R
