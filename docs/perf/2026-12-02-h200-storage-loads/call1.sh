#!/usr/bin/env bash
# Call 1 (2026-12-02): the storage blocks declared `restrict` ("The walks' storage loads, and the neighbour's kappa with its position" in
# docs/PERFORMANCE.md). Variants, each a copy of glsl/ under scratch/ made on the development machine:
#     mkdir -p scratch/base-glsl scratch/restrictro scratch/restrictall
#     for d in base-glsl restrictro restrictall; do git archive HEAD glsl | tar x -C scratch/$d; done
#     find scratch/restrictro/glsl/sim -name '*.comp' -o -name '*.glsl' | xargs sed -i -E \
#       's/layout\(std430\) readonly buffer/layout(std430) restrict readonly buffer/'
#     find scratch/restrictall/glsl/sim -name '*.comp' -o -name '*.glsl' | xargs sed -i -E \
#       's/layout\(std430\) (readonly |writeonly |)buffer/layout(std430) restrict \1buffer/'
# (restrictro: the simulation's read-only blocks; restrictall: every simulation block but the two
# coherent ones.) Runs: iteration-bench.sh's iteration at 30 iterations a solve at 246k and 1M, ten
# seconds at 246k, WCSPH at 246k (its passes a substep), PBF at 1M over the surge, each variant's
# machine code (the driver's cache) for head and restrictall.
set -u
scripts/gpu/setup-and-build.sh ranryu > /tmp/b.txt 2>&1 || { tail -30 /tmp/b.txt; exit 1; }
. scripts/gpu/env.sh x
VARIANTS="head restrictro restrictall" TEN_S_VARIANTS="head restrictro restrictall" WCSPH_VARIANTS="head restrictall" \
  timeout 400 scripts/gpu/iteration-bench.sh 2>&1 | tail -80
dx=$(python3 scripts/gpu/scene-at.py dam-break /tmp/p.json 1000000)
for v in head restrictall; do
  d=scratch/$v/glsl; [ $v = head ] && d=scratch/base-glsl/glsl
  timeout 90 $B profile --scene /tmp/p.json --solver pbf --spacing $dx --shading particles --size 640x360 --frames 20 --warmup 20 \
    --shader-dir $d --records $OUT/pbf-$v.csv > $OUT/pbf-$v.txt 2>&1
  echo "== pbf 1M $v: rc $?"; grep -E "pbf\.|frame \(GPU|fps and" $OUT/pbf-$v.txt
done
dx=$(python3 scripts/gpu/scene-at.py dam-break /tmp/w.json 246078)
for v in head restrictall; do
  d=scratch/$v/glsl; [ $v = head ] && d=scratch/base-glsl/glsl
  mkdir -p /tmp/cache-$v
  __GL_SHADER_DISK_CACHE=1 __GL_SHADER_DISK_CACHE_SKIP_CLEANUP=1 __GL_SHADER_DISK_CACHE_PATH=/tmp/cache-$v \
    timeout 60 $B profile --scene /tmp/w.json --spacing $dx --shading particles --size 640x360 --frames 3 --warmup 0 --shader-dir $d > /dev/null 2>&1
done
tar czf $OUT/caches.tgz -C /tmp cache-head cache-restrictall
tar czf $OUT/pbf.tgz -C $OUT pbf-head.csv pbf-head.txt pbf-restrictall.csv pbf-restrictall.txt && rm -f $OUT/pbf-*
