#!/usr/bin/env bash
# The dam break's candidates as sweep rows at about 250k and 1M particles (scene-settings.py --at-scale):
# DFSPH at factors 2, 1.5, 1 at 246k; 1 at 1M.
cd "$(dirname "$0")/.."
scripts/gpu/setup-and-build.sh ranryu >/dev/null 2>&1 || { echo build failed; exit 1; }
. scripts/gpu/env.sh x
mkdir -p $out/at
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $out/at/device.txt; date -u >> $out/at/device.txt
t0=$(date +%s)
sweep() { timeout $1 $B sweep --cases scene:$2 --seconds 10 --quiet --out $out/at "${@:3}" >> $out/at/sweep.log 2>&1; echo "rc $? at $(( $(date +%s) - t0 )) s: $2 ${*:3}"; }
sweep 150 dam-break --spacings 0.00317 --solvers dfsph --factors 2,1.5,1
sweep 230 dam-break --spacings 0.002 --solvers dfsph --factors 1
tail -5 $out/at/sweep.log
tar czf $out/at.tgz -C $out at && rm -rf $out/at
