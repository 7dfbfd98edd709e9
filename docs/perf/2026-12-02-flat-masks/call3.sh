#!/usr/bin/env bash
# Call 3: the machine code of the flat loop, the engine's (the driver's shader cache of a three-frame
# dam break at 246k with the tree's shaders and with flat2's, cut apart by
# docs/perf/2026-12-01-h200-kernel-constants/sass.py with the CUDA toolkit's nvdisasm) and the replica's
# (cuobjdump of walk_real.cu: accelerate_packed, the engine's loop a run, and accelerate_flat).
set -u
scripts/gpu/setup-and-build.sh ranryu > /tmp/b.txt 2>&1 || { tail -30 /tmp/b.txt; exit 1; }
. scripts/gpu/env.sh x
root=$OUT
export NVDISASM=$(dirname "$(command -v nvcc)")/nvdisasm
ls -la "$NVDISASM"; command -v zstd || echo "no zstd"
dx=$(python3 scripts/gpu/scene-at.py dam-break /tmp/w.json 246078)
for v in current flat2; do
  d=glsl; [ $v != current ] && d=scratch/$v/glsl
  mkdir -p /tmp/cache-$v "$root/sass-$v"
  __GL_SHADER_DISK_CACHE=1 __GL_SHADER_DISK_CACHE_SKIP_CLEANUP=1 __GL_SHADER_DISK_CACHE_PATH=/tmp/cache-$v \
    timeout 60 $B profile --scene /tmp/w.json --spacing $dx --shading particles --size 640x360 --frames 3 --warmup 0 --shader-dir $d > /tmp/p-$v.txt 2>&1
  echo "== $v rc $?"
  python3 docs/perf/2026-12-01-h200-kernel-constants/sass.py /tmp/cache-$v "$root/sass-$v/p" 2>&1 | tail -40
done
tar czf "$root/caches.tgz" -C /tmp cache-current cache-flat2
patch -s -o /tmp/walk_real.cu docs/perf/2026-11-29-h200-walk-floor/walk_bench.cu docs/perf/2026-12-02-replica-real-state/walk_real.patch
nvcc -O3 -arch=sm_90 -cubin /tmp/walk_real.cu -o /tmp/wr.cubin > /dev/null 2>&1
cuobjdump --dump-sass /tmp/wr.cubin > /tmp/wr.sass 2>&1 || nvdisasm -c /tmp/wr.cubin > /tmp/wr.sass 2>&1
wc -l /tmp/wr.sass; cp /tmp/wr.sass "$root/replica.sass"
(cd "$root" && tar czf sass.tgz sass-current sass-flat2 replica.sass && rm -rf sass-current sass-flat2 replica.sass)
