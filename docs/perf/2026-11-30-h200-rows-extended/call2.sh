#!/usr/bin/env bash
# Two variants of the rows against the extension's cap stops (call 1): ext2 = the rows extended from the
# fluid (scratch/ext) with the density pass's diagonal |G|·|G + B| + Σ m²|∇W|²; pull = the shipped rows'
# l1-Jacobi update pulled by 0.2 toward the extension each iteration. The dam break ten seconds at about
# 250k and 1M, the tank at 0.00625 / 0.003125 m; the pull's front at a/dx = 40.
set -u
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
scripts/gpu/setup-and-build.sh ranryu > $OUT/build.txt 2>&1 || { tail -30 $OUT/build.txt; exit 1; }
. scripts/gpu/env.sh x
export RUN_TIMEOUT=150
for v in pull ext2; do
  sh=$PWD/scratch/$v/glsl
  TAG=$v SHADERS=$sh NS="250000 1000000" ETAS=1e-3 scripts/gpu/dfsph-eta.sh 2>&1 | grep -v "why its settings" | tee $OUT/$v.txt
  for dx in 0.00625 0.003125; do
    timeout 120 $B validate hydrostatic --solver dfsph --spacing $dx --settle 1 --average 2 --shader-dir $sh --json /tmp/tank.json > /tmp/tank.txt 2>&1
    echo "== tank $dx $v rc $?"; grep -E "^floor layer|interior \(|rms speed|steps in" /tmp/tank.txt | tee -a $OUT/$v.txt
  done
done
python3 scripts/gpu/scene-at.py dam-break /tmp/db.json 1000 > /dev/null
timeout 100 $B validate dam-break --scene /tmp/db.json --solver dfsph --spacing 0.005 --shader-dir $PWD/scratch/pull/glsl --quiet > /tmp/front.txt 2>&1
echo "== front a/dx 40 pull rc $? $(grep -m1 'surge front error' /tmp/front.txt)" | tee -a $OUT/pull.txt
