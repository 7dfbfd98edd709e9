#!/usr/bin/env bash
# The tank and jet candidates as sweep rows at about 250k and 1M particles (scene-settings.py --at-scale):
# PBF as shipped (factor 1) for the jet and the tank at about 250k and 1M.
cd "$(dirname "$0")/.."
scripts/gpu/setup-and-build.sh ranryu >/dev/null 2>&1 || { echo build failed; exit 1; }
. scripts/gpu/env.sh x
mkdir -p $out/at
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $out/at/device.txt; date -u >> $out/at/device.txt
t0=$(date +%s)
sweep() { timeout $1 $B sweep --cases scene:$2 --seconds 10 --quiet --out $out/at "${@:3}" >> $out/at/sweep.log 2>&1; echo "rc $? at $(( $(date +%s) - t0 )) s: $2 ${*:3}"; }
sweep 70 turbulent-jet --spacings 0.0047 --solvers pbf --factors 1
sweep 60 hydrostatic --spacings 0.00311 --solvers pbf --factors 1
sweep 120 turbulent-jet --spacings 0.00296 --solvers pbf --factors 1
sweep 200 hydrostatic --spacings 0.00196 --solvers pbf --factors 1
tail -5 $out/at/sweep.log
tar czf $out/at.tgz -C $out at && rm -rf $out/at
