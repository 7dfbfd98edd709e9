#!/usr/bin/env bash
# The tank at rest with the rows eliminated (docs/DFSPH.md (D13)) as the engine ships it: `ranryu validate
# hydrostatic --solver dfsph` at 20, 40 and 80 layers (settled 1 s, averaged 2 s; the first two at once,
# the third alone), then the scene for ten seconds at about 250k particles alone (particle shading at
# 640x360, the guard watching), as scenes-seconds.sh runs it.
set -u
scripts/gpu/setup-and-build.sh ranryu > $OUT/build.txt 2>&1 || { tail -30 $OUT/build.txt; exit 1; }
. scripts/gpu/env.sh x
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | tee $OUT/device.txt; date -u | tee -a $OUT/device.txt
v() { timeout 300 $B validate hydrostatic --solver dfsph --spacing $1 --settle 1 --average 2 --json $OUT/v$1.json > $OUT/v$1.txt 2>&1; echo "validate $1: rc $?"; }
v 0.0125 & v 0.00625 & wait
v 0.003125
for f in $OUT/v*.txt; do echo "== $f"; grep -E "^pressure error|^rms speed|^floor layer|^interior over|steps in|^each half" $f | cut -c1-400; done
dx=$(python3 scripts/gpu/scene-at.py hydrostatic $OUT/h250k.json 250000)
timeout 330 $B profile --scene $OUT/h250k.json --solver dfsph --spacing $dx --shading particles --size 640x360 \
  --frames 600 --warmup 0 --records $OUT/tank-250k.csv > $OUT/tank-250k.txt 2>&1
echo "tank 250k: rc $? spacing $dx"
grep -E "particles|fps and real-time|substeps/frame|^guard|density solve:|^ranryu: " $OUT/tank-250k.txt | cut -c1-300 | head -14
