#!/usr/bin/env bash
# The drop's candidates as sweep rows at about 250k and 1M particles, for scene-settings.py --at-scale:
# DFSPH at factors 1-2.5 and PBF at 1 (8 substeps scaled) at 244k; the two that hold there at 960k.
scripts/gpu/setup-and-build.sh ranryu >/dev/null 2>&1 || { echo build failed; exit 1; }
. scripts/gpu/env.sh x
mkdir -p $out/at
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $out/at/device.txt; date -u >> $out/at/device.txt
t0=$(date +%s)
sweep() { timeout $1 $B sweep --cases scene:drop --seconds 10 --quiet --out $out/at "${@:2}" >> $out/at/sweep.log 2>&1; echo "rc $? at $(( $(date +%s) - t0 )) s: ${*:2}"; }
sweep 100 --spacings 0.00454 --solvers dfsph --factors 2.5,2,1.5,1
sweep 60 --spacings 0.00454 --solvers pbf --factors 1
sweep 110 --spacings 0.00286 --solvers pbf --factors 1
sweep 110 --spacings 0.00286 --solvers dfsph --factors 1
tar czf $out/at.tgz -C $out at && rm -rf $out/at
