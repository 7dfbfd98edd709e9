#!/usr/bin/env bash
# WCSPH's ten seconds of every bundled SPH scene at about 250k particles with the plan two frames back
# (issue 11: "every bundled scene runs 10 s with either solver at about 250k and 1M"; last run on the
# H100 on 2026-11-25, before the plan changed). Particle shading at 640x360, the guard watching.
# Output: one tar under $OUT, and each scene's verdict printed.
scripts/gpu/setup-and-build.sh ranryu >/dev/null 2>&1 || { echo build failed; exit 1; }
. scripts/gpu/env.sh x
r=$out/r; mkdir -p $r
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $r/device.txt; date -u >> $r/device.txt
OUT=$r SOLVER=wcsph PARTICLES=250000 RUN_TIMEOUT=${RUN_TIMEOUT:-200} scripts/gpu/scenes-seconds.sh 10
for f in $r/*.txt; do grep -hE 'fps and real-time' $f | head -1; done
tar czf $out/wcsph-250k.tgz -C $out r
