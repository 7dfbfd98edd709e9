#!/usr/bin/env bash
# The README's sweeps again on the tree of today (DFSPH with the boundary rows, (D10) on the rows, the
# peak bound, the dam break's Courant number 0.5; PBF and WCSPH as shipped): the two validation cases
# with all three solvers, then the standing wave's sweep (scripts/gpu/standing-wave.sh's grid).
scripts/gpu/setup-and-build.sh ranryu >/dev/null 2>&1 || { echo build failed; exit 1; }
. scripts/gpu/env.sh x
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $out/device.txt; date -u >> $out/device.txt
git log -1 --format=%H >> $out/device.txt
mkdir -p $out/main $out/sw
t0=$(date +%s)
timeout 330 $B sweep --out $out/main --cases dam-break,hydrostatic --spacings 0.01,0.005 --factors 0.5,1,1.5,2 --quiet > $out/main/sweep.log 2>&1
echo "main: rc $? $(( $(date +%s) - t0 )) s"
t0=$(date +%s)
timeout 170 $B sweep --out $out/sw --cases standing-wave --spacings 0.0133,0.01,0.005,0.0025 --quiet > $out/sw/sweep.log 2>&1
echo "standing wave: rc $? $(( $(date +%s) - t0 )) s"
tar czf $out/sweeps.tgz -C $out main sw && rm -rf $out/main $out/sw
