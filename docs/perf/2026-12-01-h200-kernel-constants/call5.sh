#!/usr/bin/env bash
# (D10)'s step in the residual pass: chebearly loads the particle's kappa and kappa^(k-1) before the walk
# (the same sums); chebnoload stores kappa^(k-1) without loading it (a diagnostic). Iterations fixed at
# 30 with --detail, then ten seconds at 246k of current and chebearly, and chebearly's machine code.
set -u
scripts/gpu/setup-and-build.sh ranryu > /tmp/b1.txt 2>&1 || { tail -30 /tmp/b1.txt; exit 1; }
. scripts/gpu/env.sh x
o=$OUT; nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | tee $o/device.txt; date -u | tee -a $o/device.txt
for n in 1000000 246078; do
  dx=$(python3 scripts/gpu/scene-at.py dam-break /tmp/s-$n.json $n sph.min_iterations=30 sph.max_iterations=30 sph.shrink_step_above=0)
  fr=5; wu=5; [ $n -lt 500000 ] && { fr=10; wu=20; }
  for v in current chebearly chebnoload current chebearly; do
    d=glsl; [ $v != current ] && d=scratch/$v/glsl
    export __GL_SHADER_DISK_CACHE=1 __GL_SHADER_DISK_CACHE_SKIP_CLEANUP=1 __GL_SHADER_DISK_CACHE_PATH=/tmp/cache-$v; mkdir -p /tmp/cache-$v
    f=/tmp/r-$v-$n.txt
    timeout 120 $B profile --scene /tmp/s-$n.json --spacing $dx --shading particles --size 640x360 --frames $fr --warmup $wu --detail --shader-dir $d > $f 2>&1
    echo "== $v $n rc $?"; grep -E "dfsph.pressure.(solve|correct|accelerate)|density solve:" $f
    cat $f >> $o/variants.txt
  done
done
dx=$(python3 scripts/gpu/scene-at.py dam-break /tmp/db10.json 250000)
for v in current chebearly; do
  d=glsl; [ $v != current ] && d=scratch/$v/glsl
  timeout 150 $B profile --scene /tmp/db10.json --spacing $dx --shading particles --size 640x360 --frames 600 --warmup 0 --shader-dir $d --records $o/db10-$v.csv > /tmp/t-$v.txt 2>&1
  echo "== 10 s $v rc $?"; grep -E "^dfsph.pressure|substeps/frame \(|density solve:|fps and" /tmp/t-$v.txt; cat /tmp/t-$v.txt >> $o/ten.txt
done
tar czf $o/caches.tgz -C /tmp cache-chebearly cache-current
