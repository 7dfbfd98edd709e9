#!/usr/bin/env bash
# Call 3: the machine code of every program DFSPH's and PBF's dam break use (the whole pipeline, 246k,
# five frames, each solver with a shader cache of its own), then WCSPH's dam break at 1M for ten seconds
# on this tree (the run of docs/perf/2026-11-29-h200-wcsph-1m-dam-break/run.sh), for issue 11's ratio.
set -u
scripts/gpu/setup-and-build.sh ranryu > /tmp/b.txt 2>&1 || { tail -30 /tmp/b.txt; exit 1; }
. scripts/gpu/env.sh x
r=/tmp/r; mkdir -p $r
{ nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; date -u; } | tee $r/device.txt
dx=$(python3 scripts/gpu/scene-at.py dam-break /tmp/w.json 246078)
for s in dfsph pbf; do
  __GL_SHADER_DISK_CACHE=1 __GL_SHADER_DISK_CACHE_SKIP_CLEANUP=1 __GL_SHADER_DISK_CACHE_PATH=/tmp/cache-$s \
    timeout 60 $B profile --scene /tmp/w.json --solver $s --spacing $dx --size 640x360 --frames 5 --warmup 0 > $r/cache-$s.txt 2>&1
  echo "== $s rc $?"
done
tar czf $OUT/caches.tgz -C /tmp cache-dfsph cache-pbf
timeout ${RUN_TIMEOUT:-480} $B profile --scene media/scenes/dam-break.json --solver wcsph --spacing 0.002 --frames 600 --warmup 0 \
  --shading particles --size 640x360 --records $r/db-1m.csv > $r/db-1m.txt 2>&1
echo "rc $?"; grep -E 'substeps/frame|fps and|^guard|ranryu: simulation|^ *(density|forces|integrate|frame) ' $r/db-1m.txt | grep -v 'profile: frame'
tail -c 300 $r/db-1m.txt | tr '\r' '\n' | tail -2
tar czf $OUT/runs.tgz -C /tmp r
