#!/usr/bin/env bash
# Inside the density solve at 1M: the dam break at 1,000,000 particles (spacing 0.002), particle shading at
# 640x360, `ranryu profile --detail`: the surge's frames 20-40, and the settled pool's frames 360-420 (after
# 340 untimed frames of warm-up), each dispatch of the solves timed apart.
set -u
scripts/gpu/setup-and-build.sh ranryu > /tmp/build4.txt 2>&1 || { tail -30 /tmp/build4.txt; exit 1; }
. scripts/gpu/env.sh x
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | tee $OUT/device.txt; date -u | tee -a $OUT/device.txt
for run in "surge 20 20" "settled 360 60"; do
  set -- $run
  f=$OUT/dam-1m-$1
  timeout 280 $B profile --scene dam-break --spacing 0.002 --shading particles --size 640x360 --warmup $2 --frames $3 --detail > $f.txt 2>&1
  echo "== $1 rc $?"; sed -n '/^pass /,/^$/p' $f.txt | grep -E "^ *dfsph|^frame"; grep -E "substeps/frame \(|density solve:|fps and" $f.txt
done
