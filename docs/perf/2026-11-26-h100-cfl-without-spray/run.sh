#!/usr/bin/env bash
# Experiment: DFSPH's CFL speed over the fluid only (spray, rho < 0.6 rho0, excluded; scratch/glsl-cfl):
# the dam break's frames 20-40 at 246k and 1M against the shipped shaders, and 10 s at 246k.
cd "$(dirname "$0")/.."
scripts/gpu/setup-and-build.sh ranryu >/dev/null 2>&1 || { echo build failed; exit 1; }
. scripts/gpu/env.sh x
o=$OUT/cfl; mkdir -p $o
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $o/device.txt; date -u >> $o/device.txt
for dx in 0.00317 0.002; do
  for v in base cfl; do
    sd=(); [ $v = cfl ] && sd=(--shader-dir scratch/glsl-cfl)
    timeout 200 $B profile --scene dam-break --solver dfsph --spacing $dx --size 1920x1080 --frames 20 --warmup 20 \
      "${sd[@]}" > $o/db-$v-$dx.txt 2>&1
    echo "$v $dx rc $?: $(grep -m1 'substeps/frame' $o/db-$v-$dx.txt | grep simulation) | $(grep -m1 'fps and real-time' $o/db-$v-$dx.txt)" | tee -a $o/summary.txt
  done
done
timeout 200 $B profile --scene dam-break --solver dfsph --spacing 0.00317 --shading particles --size 640x360 --frames 600 --warmup 0 \
  --shader-dir scratch/glsl-cfl --records $o/cfl-10s-0.00317.csv > $o/cfl-10s-0.00317.txt 2>&1
echo "cfl 10s 246k rc $?: $(grep -m1 '^ranryu: simulation' $o/cfl-10s-0.00317.txt || grep -m1 'fps and real-time' $o/cfl-10s-0.00317.txt) $(grep -m1 'simulation (dfsph)' $o/cfl-10s-0.00317.txt) $(grep -m1 '^guard' $o/cfl-10s-0.00317.txt)" | tee -a $o/summary.txt
cd $OUT && tar czf f.tgz cfl && rm -rf cfl
