#!/usr/bin/env bash
# After the kernel's constants: the residual pass's parts again (variants of correct_pressure.comp with
# the rows' code, (D10)'s step or the workgroup reduction left out; lean: all three), iterations fixed
# at 30, --detail; then the dam break as shipped at 1M for ten seconds.
set -u
scripts/gpu/setup-and-build.sh ranryu > /tmp/b1.txt 2>&1 || { tail -30 /tmp/b1.txt; exit 1; }
. scripts/gpu/env.sh x
o=$OUT; nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | tee $o/device.txt; date -u | tee -a $o/device.txt
for n in 1000000 246078; do
  dx=$(python3 scripts/gpu/scene-at.py dam-break /tmp/s-$n.json $n sph.min_iterations=30 sph.max_iterations=30 sph.shrink_step_above=0)
  fr=5; wu=5; [ $n -lt 500000 ] && { fr=10; wu=20; }
  for v in current norowsc nocheb noreduce lean; do
    d=glsl; [ $v != current ] && d=scratch/$v/glsl
    f=/tmp/r-$v-$n.txt
    timeout 120 $B profile --scene /tmp/s-$n.json --spacing $dx --shading particles --size 640x360 --frames $fr --warmup $wu --detail --shader-dir $d > $f 2>&1
    echo "== $v $n rc $?"; grep -E "dfsph.pressure.(solve|correct|accelerate)|density solve:" $f
    cat $f >> $o/variants.txt
  done
done
timeout 200 $B profile --scene dam-break --spacing 0.002 --shading particles --size 640x360 --frames 600 --warmup 0 --records $o/db10-1m.csv > $o/db10-1m.txt 2>&1
echo "== 10 s 1M rc $?"; grep -E "^dfsph|^frame|substeps/frame \(|density solve:|fps and|guard" $o/db10-1m.txt
