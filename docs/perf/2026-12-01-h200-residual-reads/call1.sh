#!/usr/bin/env bash
# Call 1 (prepared 2026-12-01 in docs/perf/2026-12-01-h200-wcsph-forces/, run 2026-12-01 night): the
# residual pass with every read before its first store ("The residual pass's reads before its stores" in
# docs/PERFORMANCE.md). Variants: head (the tree's glsl/ as committed), readsresidual
# (variants/readsresidual.patch: correct_pressure.comp alone) and reads (variants/reads.patch: that,
# integrate_pressure.comp and accelerate.comp), each a copy of glsl/ under scratch/ with its patch (the patches are in
# docs/perf/2026-12-01-h200-wcsph-forces/variants/):
#     mkdir -p scratch/base-glsl && git archive HEAD glsl | tar x -C scratch/base-glsl
#     for v in reads readsresidual; do mkdir -p scratch/$v && git archive HEAD glsl | tar x -C scratch/$v &&
#       (cd scratch/$v && patch -p1 < ../../docs/perf/2026-12-01-h200-wcsph-forces/variants/$v.patch); done
# The iteration's cost at 30 iterations (iteration-bench.sh: the solve's time over its iterations)
# at 246k and 1M, ten seconds at 246k with head and reads, and each variant's machine code (the driver's
# cache, one folder a variant, brought back for sass.py and loops.py).
set -u
scripts/gpu/setup-and-build.sh ranryu > /tmp/b.txt 2>&1 || { tail -30 /tmp/b.txt; exit 1; }
. scripts/gpu/env.sh x
VARIANTS="head readsresidual reads" TEN_S_VARIANTS="head reads" timeout 420 scripts/gpu/iteration-bench.sh 2>&1 | tail -40
dx=$(python3 scripts/gpu/scene-at.py dam-break /tmp/w.json 246078)
for v in head readsresidual reads; do
  d=scratch/$v/glsl; [ $v = head ] && d=scratch/base-glsl/glsl
  mkdir -p /tmp/cache-$v
  __GL_SHADER_DISK_CACHE=1 __GL_SHADER_DISK_CACHE_SKIP_CLEANUP=1 __GL_SHADER_DISK_CACHE_PATH=/tmp/cache-$v \
    timeout 60 $B profile --scene /tmp/w.json --spacing $dx --shading particles --size 640x360 --frames 3 --warmup 0 --shader-dir $d > /dev/null 2>&1
done
tar czf $OUT/caches.tgz -C /tmp cache-head cache-readsresidual cache-reads
