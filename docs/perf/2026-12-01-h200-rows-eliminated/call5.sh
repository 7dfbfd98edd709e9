#!/usr/bin/env bash
# sym7, the tank at rest at about 250k particles for ten seconds (the guard watching; particle shading
# at 640x360), as scenes-seconds.sh runs it, with the variant's shaders.
set -u
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
git apply docs/perf/2026-12-01-h200-rows-eliminated/sym7-engine.patch || exit 1
scripts/gpu/setup-and-build.sh ranryu > $OUT/build.txt 2>&1 || { tail -30 $OUT/build.txt; exit 1; }
. scripts/gpu/env.sh x
export RANRYU_PROTO_SYM7=1
dx=$(python3 scripts/gpu/scene-at.py hydrostatic /tmp/h.json 250000)
timeout 330 $B profile --scene /tmp/h.json --solver dfsph --spacing $dx --shading particles --size 640x360 \
  --frames 600 --warmup 0 --records $OUT/tank-sym7-250k.csv --shader-dir $PWD/scratch/sym7/glsl > $OUT/tank-sym7-250k.txt 2>&1
echo "rc $?"; grep -E "particles|fps and real-time|^guard|density solve:|^ranryu: " $OUT/tank-sym7-250k.txt | head -12
