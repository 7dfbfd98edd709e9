#!/usr/bin/env bash
# WCSPH's forces pass against the kernel's constants: the shaders of a800fc9 (head), this tree's
# (current), and this tree's with compute_forces.comp's gradient computed as before (wold), at 246k,
# frames 20-30 with particle shading; and the machine code of each.
set -u
scripts/gpu/setup-and-build.sh ranryu > /tmp/b8.txt 2>&1 || { tail -30 /tmp/b8.txt; exit 1; }
. scripts/gpu/env.sh x
dx=$(python3 scripts/gpu/scene-at.py dam-break /tmp/w.json 246078)
for v in head current wold; do
  d=glsl; [ $v = head ] && d=scratch/base-glsl/glsl; [ $v = wold ] && d=scratch/wold/glsl
  export __GL_SHADER_DISK_CACHE=1 __GL_SHADER_DISK_CACHE_SKIP_CLEANUP=1 __GL_SHADER_DISK_CACHE_PATH=/tmp/cache-$v; mkdir -p /tmp/cache-$v
  timeout 60 $B profile --scene /tmp/w.json --solver wcsph --spacing $dx --shading particles --size 640x360 --frames 10 --warmup 20 --shader-dir $d > $OUT/wcsph-$v.txt 2>&1
  echo "== $v rc $?"; grep -E "^(density|forces|integrate|frame) |substeps/frame \(" $OUT/wcsph-$v.txt
done
tar czf $OUT/caches.tgz -C /tmp cache-head cache-current cache-wold
