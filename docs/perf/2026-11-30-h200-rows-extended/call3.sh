#!/usr/bin/env bash
# The wall's drag tangential only (scratch/tan/glsl: the drag of (D7) with its component along the wall's
# gradient sum removed, also in the force condition's |a|): the dam break ten seconds at about 250k and
# 1M, the front at a/dx = 40. As run, the loop holds `tan` alone; the shipped shaders' runs it is set
# against are call 1's (the same binary).
set -u
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
scripts/gpu/setup-and-build.sh ranryu > $OUT/build.txt 2>&1 || { tail -30 $OUT/build.txt; exit 1; }
. scripts/gpu/env.sh x
export RUN_TIMEOUT=150
cp -r glsl /tmp/ship
for v in tan; do
  sh=/tmp/ship; [ $v = tan ] && sh=$PWD/scratch/tan/glsl
  TAG=$v SHADERS=$sh NS="250000 1000000" ETAS=1e-3 scripts/gpu/dfsph-eta.sh 2>&1 | grep -v "why its settings" | tee $OUT/$v.txt
  python3 scripts/gpu/scene-at.py dam-break /tmp/db.json 1000 > /dev/null
  timeout 100 $B validate dam-break --scene /tmp/db.json --solver dfsph --spacing 0.005 --shader-dir $sh --json $OUT/front-$v.json --quiet > $OUT/front-$v.txt 2>&1
  echo "== front a/dx 40 $v rc $? $(grep -m1 'surge front error' $OUT/front-$v.txt)" | tee -a $OUT/$v.txt
done
