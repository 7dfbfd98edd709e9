#!/usr/bin/env bash
# Call 1 (110bb25 with implicit-drag.patch, but for its force condition: `magnitude = length(a)`, the
# wall's drag implicit, docs/DFSPH.md (D7), and out of (D8)'s force condition): the dam break as shipped for ten seconds at 250k and 1M, the same with DFSPH's Courant
# number 0.75 (factor 1.5), the front at a/dx = 40 and 80, the surge at 246k at 1920x1080.
set -u
scripts/gpu/setup-and-build.sh ranryu > $OUT/build.txt 2>&1 || { tail -30 $OUT/build.txt; exit 1; }
. scripts/gpu/env.sh x
export RUN_TIMEOUT=150
TAG=drag NS="250000 1000000" ETAS=1e-3 scripts/gpu/dfsph-eta.sh 2>&1 | grep -v "why its settings" | tee $OUT/drag.txt
python3 scripts/gpu/scene-at.py dam-break $OUT/db.json 1000 > /dev/null
timeout 60 $B profile --scene $OUT/db.json --spacing 0.00317 --size 1920x1080 --frames 20 --warmup 20 > $OUT/surge.txt 2>&1
echo "== surge 246k rc $?"; grep -E "^simulation|density solve|fps and|^guard|frame \(GPU" $OUT/surge.txt
for dx in 0.005 0.0025; do
  timeout 100 $B validate dam-break --scene $OUT/db.json --solver dfsph --spacing $dx --json $OUT/front-$dx.json --quiet > $OUT/front-$dx.txt 2>&1
  echo "== front spacing $dx rc $?"; grep -E "error|steps" $OUT/front-$dx.txt | head -3
done
TAG=drag-cfl075 NS="250000 1000000" ETAS=1e-3 KEYS="sph.dfsph_cfl=0.75" scripts/gpu/dfsph-eta.sh 2>&1 | grep -v "why its settings" | tee $OUT/drag-cfl075.txt
