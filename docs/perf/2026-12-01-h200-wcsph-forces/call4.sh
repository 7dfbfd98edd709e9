#!/usr/bin/env bash
# Call 4: the machine code of every program DFSPH's and PBF's dam break use (call 3's first part, whose
# cache folders were not made), and WCSPH's dam break at 1M over its first 90 frames (to t = 1.5 s,
# past the returning wave at t = 1.28 s, where call 3's run was stopped) with Monaghan's alpha at 0.15
# and 0.2 (the scene's 0.1 otherwise).
set -u
scripts/gpu/setup-and-build.sh ranryu > /tmp/b.txt 2>&1 || { tail -30 /tmp/b.txt; exit 1; }
. scripts/gpu/env.sh x
r=/tmp/r; mkdir -p $r
{ nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; date -u; } | tee $r/device.txt
dx=$(python3 scripts/gpu/scene-at.py dam-break /tmp/w.json 246078)
for s in dfsph pbf; do
  mkdir -p /tmp/cache-$s
  __GL_SHADER_DISK_CACHE=1 __GL_SHADER_DISK_CACHE_SKIP_CLEANUP=1 __GL_SHADER_DISK_CACHE_PATH=/tmp/cache-$s \
    timeout 60 $B profile --scene /tmp/w.json --solver $s --spacing $dx --size 640x360 --frames 5 --warmup 0 > $r/cache-$s.txt 2>&1
  echo "== $s rc $?"
done
tar czf $OUT/caches.tgz -C /tmp cache-dfsph cache-pbf
for a in 0.15 0.2; do
  python3 scripts/gpu/scene-at.py dam-break /tmp/a$a.json 1000000 sph.artificial_viscosity=$a > /dev/null
  timeout 120 $B profile --scene /tmp/a$a.json --solver wcsph --spacing 0.002 --frames 90 --warmup 0 \
    --shading particles --size 640x360 --records $r/a$a.csv > $r/a$a.txt 2>&1
  echo "== alpha $a rc $?"; grep -E 'fps and|^guard|ranryu: simulation' $r/a$a.txt | grep -v 'profile: frame' | head -3
done
tar czf $OUT/runs.tgz -C /tmp r
