#!/usr/bin/env bash
# Call 4 (2026-12-02): the iteration's two passes with `#extension GL_KHR_memory_scope_semantics : enable`
# (variants/vmm.patch), to see whether the driver then issues their storage loads weak (LDG.E) rather than
# LDG.E.STRONG.SM; iteration-bench.sh at 1M, and both variants' machine code.
set -u
scripts/gpu/setup-and-build.sh ranryu > /tmp/b.txt 2>&1 || { tail -30 /tmp/b.txt; exit 1; }
. scripts/gpu/env.sh x
COUNTS=1000000 VARIANTS="head vmm" timeout 200 scripts/gpu/iteration-bench.sh 2>&1 | grep -E "^==|pressure.solve"
dx=$(python3 scripts/gpu/scene-at.py dam-break /tmp/w.json 246078)
for v in head vmm; do
  d=scratch/$v/glsl; [ $v = head ] && d=scratch/base-glsl/glsl
  mkdir -p /tmp/cache-$v
  __GL_SHADER_DISK_CACHE=1 __GL_SHADER_DISK_CACHE_SKIP_CLEANUP=1 __GL_SHADER_DISK_CACHE_PATH=/tmp/cache-$v \
    timeout 60 $B profile --scene /tmp/w.json --spacing $dx --shading particles --size 640x360 --frames 3 --warmup 0 --shader-dir $d > /tmp/p-$v.txt 2>&1
  grep -i "extension\|warn" /tmp/p-$v.txt | head -3
done
tar czf $OUT/caches.tgz -C /tmp cache-head cache-vmm
