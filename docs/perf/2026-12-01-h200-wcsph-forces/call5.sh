#!/usr/bin/env bash
# Call 5: two walks whose masked loops issue their second load after the first's arithmetic (call 4's
# machine code): PBF's correction with its wall term folded into the fluid's (variants/pbffold.patch)
# and DFSPH's prediction with its loads written first (variants/predfirst.patch), each against the tree,
# the same binary, --detail, the dam break at 1M over frames 20-30; then WCSPH's dam break at 1M for ten
# seconds with Monaghan's alpha at 0.15 (the scene's 0.1 stops at t = 1.28 s on this tree: call 3).
# Needs scratch/{pbffold,predfirst}/glsl.
set -u
scripts/gpu/setup-and-build.sh ranryu > /tmp/b.txt 2>&1 || { tail -30 /tmp/b.txt; exit 1; }
. scripts/gpu/env.sh x
r=/tmp/r; mkdir -p $r
{ nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; date -u; } | tee $r/device.txt
for v in tree:pbf pbffold:pbf tree:dfsph predfirst:dfsph; do
  d=${v%%:*}; s=${v##*:}; g=glsl; [ $d != tree ] && g=scratch/$d/glsl
  timeout 60 $B profile --scene dam-break --solver $s --spacing 0.002 --shading particles --size 640x360 --frames 10 --warmup 20 --detail --shader-dir $g > $r/$s-$d.txt 2>&1
  echo "== $s $d rc $?"; grep -E "^ *(pbf|dfsph)[.a-z]*(correct|predict|lambda)|^ *frame " $r/$s-$d.txt | head -6
done
python3 scripts/gpu/scene-at.py dam-break /tmp/a.json 1000000 sph.artificial_viscosity=0.15 > /dev/null
timeout 470 $B profile --scene /tmp/a.json --solver wcsph --spacing 0.002 --frames 600 --warmup 0 \
  --shading particles --size 640x360 --records $r/wcsph-1m-a0.15.csv > $r/wcsph-1m-a0.15.txt 2>&1
echo "rc $?"; grep -E 'substeps/frame|fps and|^guard|ranryu: simulation|^ *(density|forces|integrate|frame) ' $r/wcsph-1m-a0.15.txt | grep -v 'profile: frame'
tail -c 300 $r/wcsph-1m-a0.15.txt | tr '\r' '\n' | tail -2
tar czf $OUT/runs.tgz -C /tmp r
