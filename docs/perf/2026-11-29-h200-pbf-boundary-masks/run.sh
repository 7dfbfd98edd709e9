#!/usr/bin/env bash
# The branch's PBF boundary masks (the tree) against main's files (scratch/main-files), built one after
# the other on the GPU host: the dam break with PBF at 246k and 1M, frames 20-40 at 1920x1080 with the
# water shading, and two seconds at 1M with particle shading and records.
set -uo pipefail
o=$OUT/ab; mkdir -p $o
. scripts/gpu/env.sh x > /dev/null
{ nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; date -u; } | tee $o/device.txt
for v in branch main; do
  if [ $v = main ]; then cp -r scratch/main-files/* . && cmake --build build/gpu -j 16 --target ranryu > $o/build-main.txt 2>&1 || { tail $o/build-main.txt; exit 1; }; fi
  for dx in 0.00317 0.002; do
    timeout 120 $B profile --scene dam-break --solver pbf --spacing $dx --size 1920x1080 --frames 20 --warmup 20 > $o/$v-$dx.txt 2>&1
    echo "== $v $dx rc $?"; grep -E "^pbf\.|frame \(GPU|fps and|device memory" $o/$v-$dx.txt
  done
  timeout 150 $B profile --scene dam-break --solver pbf --spacing 0.002 --shading particles --size 640x360 --frames 120 --warmup 0 --records $o/$v-1m.csv > $o/$v-1m.txt 2>&1
  echo "== $v 1M 2 s rc $?"; grep -E "^pbf\.|frame \(GPU|fps and" $o/$v-1m.txt
done
cmp $o/branch-1m.csv $o/main-1m.csv && echo "1M records: the same"
tar czf $OUT/ab.tgz -C $OUT ab && rm -rf $o
