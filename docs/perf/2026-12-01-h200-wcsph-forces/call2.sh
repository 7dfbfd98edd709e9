#!/usr/bin/env bash
# Call 2: WCSPH's forces pass in four versions of glsl/: cur (HEAD's, 3d206ad), wold (cur with the
# gradient computed as before the kernel's constants: ../2026-12-01-h200-kernel-constants/variants/wold.patch),
# fold (this tree: the pair's four accumulators folded into two, the wall's term into the pressure's)
# and first (fold with the neighbour's two loads written before its gradient: variants/first.patch),
# the same binary, the dam break at 246k (frames 20-30) and 1M (frames 8-12), particle shading; the
# driver's shader cache kept for the machine code. Needs scratch/{cur,wold,first}/glsl.
set -u
scripts/gpu/setup-and-build.sh ranryu > /tmp/b.txt 2>&1 || { tail -30 /tmp/b.txt; exit 1; }
. scripts/gpu/env.sh x
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; date -u
d246=$(python3 scripts/gpu/scene-at.py dam-break /tmp/w.json 246078)
d1m=$(python3 scripts/gpu/scene-at.py dam-break /tmp/w.json 1000000)
mkdir -p /tmp/r
for v in cur wold fold first; do
  d=glsl; [ $v != fold ] && d=scratch/$v/glsl
  export __GL_SHADER_DISK_CACHE=1 __GL_SHADER_DISK_CACHE_SKIP_CLEANUP=1 __GL_SHADER_DISK_CACHE_PATH=/tmp/cache-$v; mkdir -p /tmp/cache-$v
  timeout 60 $B profile --scene /tmp/w.json --solver wcsph --spacing $d246 --shading particles --size 640x360 --frames 10 --warmup 20 --shader-dir $d > /tmp/r/wcsph246-$v.txt 2>&1
  echo "== $v 246k rc $?"; grep -E "^ *(density|forces|integrate|frame) |substeps/frame" /tmp/r/wcsph246-$v.txt | head -8
  timeout 90 $B profile --scene /tmp/w.json --solver wcsph --spacing $d1m --shading particles --size 640x360 --frames 4 --warmup 8 --shader-dir $d > /tmp/r/wcsph1m-$v.txt 2>&1
  echo "== $v 1M rc $?"; grep -E "^ *(density|forces|integrate|frame) |substeps/frame" /tmp/r/wcsph1m-$v.txt | head -8
done
unset __GL_SHADER_DISK_CACHE __GL_SHADER_DISK_CACHE_SKIP_CLEANUP __GL_SHADER_DISK_CACHE_PATH
tar czf $OUT/caches.tgz -C /tmp cache-cur cache-wold cache-fold cache-first
tar czf $OUT/runs.tgz -C /tmp r
