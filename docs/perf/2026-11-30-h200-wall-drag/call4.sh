#!/usr/bin/env bash
# Call 4 (the tree of implicit-drag.patch on 110bb25 with the iteration cap of call 3: the wall's drag
# implicit, (D8)'s force condition on its explicit strength as before): the dam break for ten
# seconds at 250k and 1M, over the surge at 246k at 1920x1080, its front at a/dx = 40 and 80.
set -u
scripts/gpu/setup-and-build.sh ranryu > $OUT/build.txt 2>&1 || { tail -30 $OUT/build.txt; exit 1; }
. scripts/gpu/env.sh x
export RUN_TIMEOUT=150
TAG=final NS="250000 1000000" ETAS=1e-3 scripts/gpu/dfsph-eta.sh 2>&1 | grep -v "why its settings" | tee $OUT/final.txt
python3 scripts/gpu/scene-at.py dam-break $OUT/db.json 1000 > /dev/null
timeout 60 $B profile --scene $OUT/db.json --spacing 0.00317 --size 1920x1080 --frames 20 --warmup 20 > $OUT/surge.txt 2>&1
echo "== surge 246k rc $?"; grep -E "^simulation|density solve|fps and|^guard" $OUT/surge.txt
for dx in 0.005 0.0025; do
  timeout 100 $B validate dam-break --scene $OUT/db.json --solver dfsph --spacing $dx --json $OUT/front-$dx.json --quiet > $OUT/front-$dx.txt 2>&1
  echo "== front spacing $dx rc $?"; grep -E "error|steps" $OUT/front-$dx.txt | head -3
done
tar czf $OUT/call4-small.tgz -C $OUT $(cd $OUT && ls *.txt *.json) && rm -f $OUT/front-*.json $OUT/front-*.txt $OUT/surge.txt
