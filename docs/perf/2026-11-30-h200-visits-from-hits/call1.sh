#!/usr/bin/env bash
# The density walk's visits from the hits' bits: HEAD's shaders (head) against this tree's (current).
# Same trajectories (llvmpipe records equal to the byte), so the passes' ms compare directly.
set -uo pipefail
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
scripts/gpu/setup-and-build.sh ranryu > $OUT/build.txt 2>&1 || { tail -30 $OUT/build.txt; exit 1; }
. scripts/gpu/env.sh x
o=$OUT/walk; mkdir -p $o
{ nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; date -u; git log -1 --format=%h; } | tee $o/device.txt
cp -r scratch/base-glsl/glsl /tmp/head; cp -r glsl /tmp/current
pat='dfsph\.density|^density |^forces|pbf\.lambda|dfsph\.pressure\.solve|frame \(GPU|fps and|^simulation'
for s in dfsph wcsph pbf; do for dx in 0.00317 0.002; do for v in head current; do
  f=$o/surge-$s-$dx-$v
  timeout 120 $B profile --scene dam-break --solver $s --spacing $dx --size 1920x1080 --frames 20 --warmup 20 \
    --shader-dir /tmp/$v --records $f.csv --json $f.json > $f.txt 2>&1
  echo "== $s $dx $v rc $?"; grep -E "$pat" $f.txt
done; done; done
for v in head current; do
  f=$o/ten-246k-$v
  timeout 100 $B profile --scene dam-break --spacing 0.00317 --shading particles --size 640x360 --frames 600 --warmup 0 \
    --shader-dir /tmp/$v --records $f.csv --json $f.json > $f.txt 2>&1
  echo "== ten 246k $v rc $?"; grep -E "$pat" $f.txt
done
for v in current head; do
  f=$o/ten-1m-$v
  timeout 140 $B profile --scene dam-break --spacing 0.002 --shading particles --size 640x360 --frames 600 --warmup 0 \
    --shader-dir /tmp/$v --records $f.csv --json $f.json > $f.txt 2>&1
  echo "== ten 1m $v rc $?"; grep -E "$pat" $f.txt
done
for f in $o/*.csv; do md5sum $f; done | sed "s|$o/||"
(cd $OUT && tar czf walk.tgz walk && rm -rf walk)
