#!/usr/bin/env bash
# The shipped split (DFSPH's density pass and PBF's lambda walk; WCSPH's as before): the three test
# programs on the H200, the passes against HEAD's shaders, and DFSPH's ten seconds.
set -uo pipefail
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
start=$(date +%s)
scripts/gpu/setup-and-build.sh all > $OUT/build.txt 2>&1 || { tail -30 $OUT/build.txt; exit 1; }
echo "built in $(( $(date +%s) - start )) s"
OUT=$OUT/tests scripts/gpu/tests.sh
. scripts/gpu/env.sh x
o=$OUT/walk; mkdir -p $o
{ nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; date -u; } | tee $o/device.txt
cp -r scratch/base-glsl/glsl /tmp/head; cp -r glsl /tmp/current
pat='dfsph\.density|^density |^forces|pbf\.lambda|frame \(GPU|fps and|^simulation'
for s in dfsph pbf wcsph; do for dx in 0.00317 0.002; do for v in head current; do
  [ $s = wcsph ] && [ $dx = 0.002 ] && continue
  f=$o/surge-$s-$dx-$v
  timeout 100 $B profile --scene dam-break --solver $s --spacing $dx --size 1920x1080 --frames 20 --warmup 20 \
    --shader-dir /tmp/$v --records $f.csv > $f.txt 2>&1
  echo "== $s $dx $v rc $?"; grep -E "$pat" $f.txt
done; done; done
f=$o/ten-246k-1080p
timeout 100 $B profile --scene dam-break --spacing 0.00317 --size 1920x1080 --frames 600 --warmup 0 \
  --records $f.csv --json $f.json > $f.txt 2>&1
echo "== ten 246k whole pipeline rc $?"; grep -E "$pat" $f.txt
f=$o/ten-1m
timeout 140 $B profile --scene dam-break --spacing 0.002 --shading particles --size 640x360 --frames 600 --warmup 0 \
  --records $f.csv --json $f.json > $f.txt 2>&1
echo "== ten 1m rc $?"; grep -E "$pat" $f.txt
(cd $OUT && tar czf walk.tgz walk tests && rm -rf walk tests)
