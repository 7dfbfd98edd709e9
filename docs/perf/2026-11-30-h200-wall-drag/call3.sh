#!/usr/bin/env bash
# Call 3 (call 1's tree with the iteration cap scaled to a plan of longer steps, iterations_at_plan()):
# the dam break for ten seconds at 250k and 1M as shipped and with (D8)'s band top at 15
# (sph.shrink_step_above), each also over the surge at 246k at 1920x1080 and its front at a/dx = 40
# and 80.
set -u
scripts/gpu/setup-and-build.sh ranryu > $OUT/build.txt 2>&1 || { tail -30 $OUT/build.txt; exit 1; }
. scripts/gpu/env.sh x
export RUN_TIMEOUT=150
for band in 20 15; do
  TAG=cap-band$band NS="250000 1000000" ETAS=1e-3 KEYS="sph.shrink_step_above=$band" scripts/gpu/dfsph-eta.sh 2>&1 | grep -v "why its settings" | tee $OUT/cap-band$band.txt
  python3 scripts/gpu/scene-at.py dam-break $OUT/db-band$band.json 1000 sph.shrink_step_above=$band > /dev/null
  timeout 60 $B profile --scene $OUT/db-band$band.json --spacing 0.00317 --size 1920x1080 --frames 20 --warmup 20 > $OUT/surge-band$band.txt 2>&1
  echo "== surge 246k band $band rc $?"; grep -E "^simulation|density solve|fps and|^guard" $OUT/surge-band$band.txt
  for dx in 0.005 0.0025; do
    timeout 100 $B validate dam-break --scene $OUT/db-band$band.json --solver dfsph --spacing $dx --json $OUT/front-band$band-$dx.json --quiet > $OUT/front-band$band-$dx.txt 2>&1
    echo "== front band $band spacing $dx rc $?"; grep -E "error|steps" $OUT/front-band$band-$dx.txt | head -3
  done
done
tar czf $OUT/call3-small.tgz -C $OUT $(cd $OUT && ls *.txt *.json) && rm -f $OUT/front-*.json $OUT/front-*.txt $OUT/surge-*.txt
