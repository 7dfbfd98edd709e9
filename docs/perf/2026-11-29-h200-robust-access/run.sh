#!/usr/bin/env bash
# A/B: the landed context (robust buffer access) against the patch (lose-context-on-reset alone).
set -uo pipefail
cd "$(dirname "$0")/.."
scripts/gpu/setup-and-build.sh ranryu > $OUT/build-a.txt 2>&1 || { tail -30 $OUT/build-a.txt; exit 1; }
cp build/gpu/app/ranryu /tmp/ranryu-robust
patch -p1 < scratch/norobust.patch
cmake --build build/gpu -j 16 --target ranryu > $OUT/build-b.txt 2>&1 || { tail -30 $OUT/build-b.txt; exit 1; }
cp build/gpu/app/ranryu /tmp/ranryu-lose
export __EGL_VENDOR_LIBRARY_FILENAMES=/usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json
mkdir -p $OUT/ab
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $OUT/ab/device.txt; date -u >> $OUT/ab/device.txt
dx246=$(python3 scripts/gpu/scene-at.py dam-break $OUT/ab/db.json 250000)
dx1m=$(python3 scripts/gpu/scene-at.py dam-break $OUT/ab/db.json 1000000)
for v in robust lose; do
  b=/tmp/ranryu-$v
  $b profile --scene dam-break --spacing $dx246 --shading particles --size 640x360 --frames 120 --warmup 0 --records $OUT/ab/db246-$v.csv > $OUT/ab/db246-$v.txt 2>&1; echo "$v db246 rc $?"
  $b profile --scene dam-break --spacing $dx1m --shading particles --size 640x360 --frames 40 --warmup 0 --records $OUT/ab/db1m-$v.csv > $OUT/ab/db1m-$v.txt 2>&1; echo "$v db1m rc $?"
  $b profile --scene dam-break --solver pbf --spacing $dx1m --shading particles --size 640x360 --frames 60 --warmup 0 --records $OUT/ab/pbf1m-$v.csv > $OUT/ab/pbf1m-$v.txt 2>&1; echo "$v pbf1m rc $?"
  $b profile --scene dam-break --spacing $dx246 --size 1920x1080 --frames 20 --warmup 20 > $OUT/ab/full246-$v.txt 2>&1; echo "$v full246 rc $?"
done
md5sum $OUT/ab/*.csv
for f in db246 db1m pbf1m full246; do
  for v in robust lose; do echo "== $f $v"; grep -E "^(hash|reorder|sort.scatter|dfsph|pbf|frame|draw|surface|level|mc)|fps and real|not robust" $OUT/ab/$f-$v.txt | head -40; done
done
tar czf $OUT/ab.tgz -C $OUT ab && rm -rf $OUT/ab
