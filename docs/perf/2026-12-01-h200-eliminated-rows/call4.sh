#!/usr/bin/env bash
# The lead of call 3 at 80 layers: `validate hydrostatic` at 0.003125 m (settled 1 s, averaged 2 s) with
# the scene's most iterations at 40 and at 60, both at once.
set -u
scripts/gpu/setup-and-build.sh ranryu > $OUT/build.txt 2>&1 || { tail -30 $OUT/build.txt; exit 1; }
. scripts/gpu/env.sh x
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | tee $OUT/device.txt; date -u | tee -a $OUT/device.txt
v() { python3 scripts/gpu/scene-at.py hydrostatic $OUT/h$1.json 3840 sph.max_iterations=$1 > /dev/null
      timeout 200 $B validate hydrostatic --scene $OUT/h$1.json --solver dfsph --spacing 0.003125 --settle 1 --average 2 > $OUT/v$1-0.003125.txt 2>&1
      echo "validate most $1: rc $?"; }
v 40 & v 60 & wait
for f in $OUT/v*-0.003125.txt; do echo "== $f"; grep -E "^pressure error|^rms speed|^floor layer|^interior over|steps in|^each half" $f | cut -c1-300; done
