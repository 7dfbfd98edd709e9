#!/usr/bin/env bash
# Call 1 (2026-12-02): the particles' impostors by the compute raster (docs/RENDERING.md (R15)) against
# the instanced draw (RANRYU_PARTICLE_RASTER=draw), one binary.
# 1. the render tests (the CPU ray caster) on the H200, both rasters;
# 2. the dam break at 1M with particle shading, 30 frames after 10, at 640x360 and at 1920x1080, each
#    raster (the passes within draw-particles timed apart with --detail on the compute raster's second
#    run); the simulation is the same, so only the draw differs;
# 3. the dam break as shipped with DFSPH for ten seconds at 1M, particles at 640x360 (issue 11's figure).
set -u
scripts/gpu/setup-and-build.sh all > /tmp/b.txt 2>&1 || { tail -30 /tmp/b.txt; exit 1; }
. scripts/gpu/env.sh x
root=$OUT
mkdir -p "$root/short"
build/gpu/tests/ranryu_gl_tests "render:*" > "$root/short/render-tests.txt" 2>&1
echo "== render tests rc $?: $(tail -2 "$root/short/render-tests.txt" | head -1)"
f="$root/short/db-1m.json"
dx=$(python3 scripts/gpu/scene-at.py dam-break "$f" 1000000)
for size in 640x360 1920x1080; do
  for raster in draw compute; do
    RANRYU_PARTICLE_RASTER=$raster timeout 60 "$B" profile --scene "$f" --spacing "$dx" --shading particles --size $size \
      --frames 30 --warmup 10 > "$root/short/$raster-$size.txt" 2>&1
    echo "== $raster $size rc $?: $(grep -E '^draw-particles|^frame \(GPU' "$root/short/$raster-$size.txt" | tr -s ' ' | tr '\n' '|')"
  done
  timeout 60 "$B" profile --scene "$f" --spacing "$dx" --shading particles --size $size --frames 30 --warmup 10 --detail \
    > "$root/short/detail-$size.txt" 2>&1
  grep -E "draw-particles" "$root/short/detail-$size.txt"
done
(cd "$root" && tar czf short.tgz short && rm -rf short)
OUT=$root/db-1m SOLVER=dfsph PARTICLES=1000000 SCENES=dam-break RUN_TIMEOUT=130 timeout 140 scripts/gpu/scenes-seconds.sh 10 2>&1 | tail -4
grep -E "^draw-particles|^frame \(GPU|fps and real-time" "$root/db-1m/dam-break.txt"
(cd "$root" && tar czf db-1m.tgz db-1m && rm -rf db-1m)
