#!/usr/bin/env bash
# Session 32, call 4: the density passes skipping the cells whose box lies beyond h (density_walk.glsl,
# NEIGHBOUR_RUN_NEAR) against HEAD's shaders: the dam break over the surge (frames 20-40), particle
# shading at 640x360, DFSPH at 246k and 1M, WCSPH at 246k, PBF at 1M; each pass's time.
set -u
scripts/gpu/setup-and-build.sh ranryu > $OUT/build.txt 2>&1 || { tail -30 $OUT/build.txt; exit 1; }
. scripts/gpu/env.sh call4
o=$OUT/trim; mkdir -p $o
{ nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; date -u; git log -1 --format=%h; } | tee $o/device.txt
for cfg in "dfsph 246078" "dfsph 1000000" "wcsph 246078" "pbf 1000000"; do
  set -- $cfg
  dx=$(python3 scripts/gpu/scene-at.py dam-break $o/scene-$2.json $2)
  for v in head current; do
    sd=glsl; [ $v = head ] && sd=scratch/base-glsl/glsl
    f=$o/$1-$2-$v
    timeout 100 $B profile --scene $o/scene-$2.json --solver $1 --spacing $dx --shading particles --size 640x360 \
      --frames 20 --warmup 20 --shader-dir $sd --records $f.csv > $f.txt 2>&1
    echo "== $1 $2 $v: rc $?"
    grep -E '^(dfsph\.density|density|pbf\.lambda|dfsph\.pressure\.solve|frame \(GPU)|fps and' $f.txt
  done
done
(cd $OUT && tar czf trim.tgz trim && rm -rf trim)
