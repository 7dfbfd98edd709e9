#!/usr/bin/env bash
# Call 3: issue 11's and 12's table again with the tree as it ships (no-slip walls, the scaled cap, the
# divergence warm start as its impulse): the dam break's whole pipeline (water shading at 1920x1080)
# over frames 20-40, each solver as the scene ships it, at 64k-1M (`bench-dfsph.sh`); then ten seconds
# of DFSPH at 246k with the whole pipeline at 1920x1080 (the real-time measure, not the
# particle shading of the other ten-second runs).
set -u
scripts/gpu/setup-and-build.sh ranryu > $OUT/build.txt 2>&1 || { tail -30 $OUT/build.txt; exit 1; }
. scripts/gpu/env.sh x
mkdir -p bench
OUT=$PWD/bench scripts/gpu/bench-dfsph.sh "dfsph wcsph pbf" "0.005 0.004 0.00317 0.0025 0.002" 20 20 2>&1 | tee $OUT/side-by-side.txt
timeout 120 $B profile --scene dam-break --spacing 0.00317 --size 1920x1080 --frames 600 --warmup 0 \
  --records bench/db-246k-10s-1080p.csv --json bench/db-246k-10s-1080p.json > bench/db-246k-10s-1080p.txt 2>&1
echo "== ten seconds at 246k, 1920x1080: rc $?" | tee -a $OUT/side-by-side.txt
grep -vE "^why its settings" bench/db-246k-10s-1080p.txt | tail -45 | tee -a $OUT/side-by-side.txt
tar czf $OUT/bench.tgz bench
