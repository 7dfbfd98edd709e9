#!/usr/bin/env bash
# More variants of correct_pressure.comp (nochebrows: the rows' (D10) step left out; chebalways: (D10)'s
# step without its iteration test; rowscheb0: the rows' code and (D10) left out, the reduction kept), and
# each variant's NVIDIA shader cache (its machine code) brought back for the register counts.
set -u
scripts/gpu/setup-and-build.sh ranryu > /tmp/b1.txt 2>&1 || { tail -30 /tmp/b1.txt; exit 1; }
. scripts/gpu/env.sh x
o=$OUT; nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | tee $o/device.txt; date -u | tee -a $o/device.txt
export __GL_SHADER_DISK_CACHE=1 __GL_SHADER_DISK_CACHE_SKIP_CLEANUP=1
n=1000000
dx=$(python3 scripts/gpu/scene-at.py dam-break /tmp/s-$n.json $n sph.min_iterations=30 sph.max_iterations=30 sph.shrink_step_above=0)
for v in current nochebrows chebalways rowscheb0 lean norowsc nocheb; do
  d=glsl; [ $v != current ] && d=scratch/$v/glsl
  export __GL_SHADER_DISK_CACHE_PATH=/tmp/cache-$v; mkdir -p $__GL_SHADER_DISK_CACHE_PATH
  f=/tmp/r-$v-$n.txt
  timeout 120 $B profile --scene /tmp/s-$n.json --spacing $dx --shading particles --size 640x360 --frames 5 --warmup 5 --detail --shader-dir $d > $f 2>&1
  echo "== $v $n rc $?"; grep -E "dfsph.pressure.(correct|accelerate)|density solve:" $f
  cat $f >> $o/runs.txt
done
tar czf $o/caches.tgz -C /tmp $(cd /tmp && ls -d cache-*)
ls -la $o
