#!/usr/bin/env bash
# The kernel's constants as operands (SphParams inv_h, w_scale, grad_scale): git HEAD's shaders
# against this tree's on the same binary: iterations fixed at 30 (the solve's time over 30 is an
# iteration), and the dam break as shipped for ten seconds at 246k; then this tree's shader cache.
set -u
scripts/gpu/setup-and-build.sh ranryu > /tmp/b1.txt 2>&1 || { tail -30 /tmp/b1.txt; exit 1; }
. scripts/gpu/env.sh x
export __GL_SHADER_DISK_CACHE=1 __GL_SHADER_DISK_CACHE_SKIP_CLEANUP=1 __GL_SHADER_DISK_CACHE_PATH=/tmp/cache-run; mkdir -p /tmp/cache-run
VARIANTS="head current" TEN_S_VARIANTS="head current" OUT=/tmp/bench bash scripts/gpu/iteration-bench.sh 2>&1 | grep -vE "^  (divergence|the step)" | grep -E "^==|dfsph\.(density|pressure|divergence|integrate)|density solve|fps and"
cp /tmp/bench/bench.tgz $OUT/
n=1000000; dx=$(python3 scripts/gpu/scene-at.py dam-break /tmp/s-$n.json $n sph.min_iterations=30 sph.max_iterations=30 sph.shrink_step_above=0)
for v in head current; do
  d=glsl; [ $v = head ] && d=scratch/base-glsl/glsl
  export __GL_SHADER_DISK_CACHE_PATH=/tmp/cache-$v; mkdir -p $__GL_SHADER_DISK_CACHE_PATH
  timeout 120 $B profile --scene /tmp/s-$n.json --spacing $dx --shading particles --size 640x360 --frames 5 --warmup 5 --detail --shader-dir $d > /tmp/d-$v.txt 2>&1
  echo "== detail $v rc $?"; grep -E "^ *dfsph|^frame" /tmp/d-$v.txt; cat /tmp/d-$v.txt >> $OUT/detail.txt
done
tar czf $OUT/caches.tgz -C /tmp cache-head cache-current
