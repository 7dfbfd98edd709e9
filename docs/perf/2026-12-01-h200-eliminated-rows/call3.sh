#!/usr/bin/env bash
# A lead, not shipped: the tank issues its cap of 100 density iterations a step (it stops steps at the cap,
# and a stop sends the cap back to the scene's most) and runs about 13, so with (D13) most of its solve's
# time is empty dispatches. The scene's most lowered to 40 (sph.max_iterations=40): the tank at 246k for
# ten seconds, and `validate hydrostatic` at 20 and 40 layers (settled 1 s, averaged 2 s, both at once).
set -u
scripts/gpu/setup-and-build.sh ranryu > $OUT/build.txt 2>&1 || { tail -30 $OUT/build.txt; exit 1; }
. scripts/gpu/env.sh x
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | tee $OUT/device.txt; date -u | tee -a $OUT/device.txt
python3 scripts/gpu/scene-at.py hydrostatic $OUT/h40.json 3840 sph.max_iterations=40 > /dev/null
v() { timeout 200 $B validate hydrostatic --scene $OUT/h40.json --solver dfsph --spacing $1 --settle 1 --average 2 > $OUT/v40-$1.txt 2>&1; echo "validate $1: rc $?"; }
v 0.0125 & v 0.00625 & wait
for f in $OUT/v40-*.txt; do echo "== $f"; grep -E "^pressure error|^rms speed|^floor layer|^interior over|steps in|^each half" $f | cut -c1-300; done
dx=$(python3 scripts/gpu/scene-at.py hydrostatic $OUT/t40.json 250000 sph.max_iterations=40)
timeout 300 $B profile --scene $OUT/t40.json --solver dfsph --spacing $dx --shading particles --size 640x360 \
  --frames 600 --warmup 0 --records $OUT/tank40-250k.csv > $OUT/tank40-250k.txt 2>&1
echo "tank 250k max_iterations 40: rc $?"
grep -E "substeps/frame \(|density solve:|fps and real|^dfsph.pressure|^ranryu: |guard" $OUT/tank40-250k.txt | grep -v "why its" | cut -c1-250
