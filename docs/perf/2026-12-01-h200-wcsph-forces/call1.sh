#!/usr/bin/env bash
# Call 1: WCSPH's forces pass against the kernel's constants (the shaders of a800fc9 "head", this tree's
# "current", and this tree's with compute_forces.comp's gradient computed as before, "wold":
# docs/perf/2026-12-01-h200-kernel-constants/variants/wold.patch), at 246k, frames 20-30 with particle
# shading, with the driver's shader cache kept for their machine code; then DFSPH's other bundled
# scenes for ten seconds at about 250k (and the drop and the jet at 1M), the guard watching.
# Needs scratch/base-glsl/glsl (git archive a800fc9 glsl) and scratch/wold/glsl (glsl + wold.patch).
set -u
scripts/gpu/setup-and-build.sh ranryu > /tmp/b.txt 2>&1 || { tail -30 /tmp/b.txt; exit 1; }
. scripts/gpu/env.sh x
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; date -u
dx=$(python3 scripts/gpu/scene-at.py dam-break /tmp/w.json 246078)
for v in head current wold; do
  d=glsl; [ $v = head ] && d=scratch/base-glsl/glsl; [ $v = wold ] && d=scratch/wold/glsl
  export __GL_SHADER_DISK_CACHE=1 __GL_SHADER_DISK_CACHE_SKIP_CLEANUP=1 __GL_SHADER_DISK_CACHE_PATH=/tmp/cache-$v; mkdir -p /tmp/cache-$v
  timeout 60 $B profile --scene /tmp/w.json --solver wcsph --spacing $dx --shading particles --size 640x360 --frames 10 --warmup 20 --shader-dir $d > $OUT/wcsph-$v.txt 2>&1
  echo "== $v rc $?"; grep -E "^ *(density|forces|integrate|frame) |substeps/frame" $OUT/wcsph-$v.txt | head -8
done
unset __GL_SHADER_DISK_CACHE __GL_SHADER_DISK_CACHE_SKIP_CLEANUP __GL_SHADER_DISK_CACHE_PATH
tar czf $OUT/caches.tgz -C /tmp cache-head cache-current cache-wold
OUT=$OUT/s250k SOLVER=dfsph PARTICLES=250000 SCENES="drop turbulent-jet hydrostatic" RUN_TIMEOUT=120 scripts/gpu/scenes-seconds.sh 10
OUT=$OUT/s1m SOLVER=dfsph PARTICLES=1000000 SCENES="drop turbulent-jet" RUN_TIMEOUT=130 scripts/gpu/scenes-seconds.sh 10
