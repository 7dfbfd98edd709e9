#!/usr/bin/env bash
# Call 6 (the tree of 13fbf25): DFSPH's no-slip walls at sph.boundary_viscosity 1e-3: the dam break for
# ten seconds at 1M, over the surge at 246k with the whole pipeline at 1920x1080, and the front at
# a/dx = 40 and 80.
set -u
scripts/gpu/setup-and-build.sh ranryu > $OUT/build.txt 2>&1 || { tail -30 $OUT/build.txt; exit 1; }
. scripts/gpu/env.sh x
python3 scripts/gpu/scene-at.py dam-break $OUT/db-noslip3.json 1000 sph.boundary_viscosity=1e-3 > /dev/null
for dx in 0.005 0.0025; do
  timeout 100 $B validate dam-break --scene $OUT/db-noslip3.json --solver dfsph --spacing $dx --json $OUT/front-$dx.json --quiet > $OUT/front-$dx.txt 2>&1
  echo "== front 1e-3 spacing $dx rc $?"; grep -E "error|steps" $OUT/front-$dx.txt | head -3
done
timeout 100 $B profile --scene $OUT/db-noslip3.json --spacing 0.00317 --size 1920x1080 --frames 20 --warmup 20 > $OUT/surge.txt 2>&1
echo "== surge 246k 1e-3 rc $?"; grep -E "^simulation|density solve|fps and|^guard|frame \(GPU" $OUT/surge.txt
export RUN_TIMEOUT=200
TAG=noslip3-1m NS="1000000" ETAS=1e-3 KEYS="sph.boundary_viscosity=1e-3" scripts/gpu/dfsph-eta.sh 2>&1 | grep -v "why its settings" | tee $OUT/noslip3-1m.txt
