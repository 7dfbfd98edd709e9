#!/usr/bin/env bash
# Call 2 (2026-12-02): the iteration's neighbour fetches through buffer textures (texelFetch), which the
# driver issues as texture loads, where a storage block's loads are LDG.E.STRONG.SM. The engine with
# `engine-fetch.patch` (Dfsph binds texture views of the positions, kappa and the pressure accelerations
# at units 0-2 for its iterations and adds GL_TEXTURE_FETCH_BARRIER_BIT to their barriers; shaders that
# declare no sampler are unaffected), the shaders: head, texpos (variants/texpos.patch: the neighbours'
# positions in the masked walks of the accelerate and residual passes) and texall (variants/texall.patch:
# and kappa_j, a_j). Runs: iteration-bench.sh at 246k and 1M, ten seconds at 246k; machine code.
set -u
scripts/gpu/setup-and-build.sh ranryu > /tmp/b.txt 2>&1 || { tail -30 /tmp/b.txt; exit 1; }
. scripts/gpu/env.sh x
VARIANTS="head texpos texall" TEN_S_VARIANTS="head texpos texall" timeout 400 scripts/gpu/iteration-bench.sh 2>&1 | tail -60
dx=$(python3 scripts/gpu/scene-at.py dam-break /tmp/w.json 246078)
for v in texall; do
  mkdir -p /tmp/cache-$v
  __GL_SHADER_DISK_CACHE=1 __GL_SHADER_DISK_CACHE_SKIP_CLEANUP=1 __GL_SHADER_DISK_CACHE_PATH=/tmp/cache-$v \
    timeout 60 $B profile --scene /tmp/w.json --spacing $dx --shading particles --size 640x360 --frames 3 --warmup 0 --shader-dir scratch/$v/glsl > /dev/null 2>&1
done
tar czf $OUT/caches.tgz -C /tmp cache-texall
