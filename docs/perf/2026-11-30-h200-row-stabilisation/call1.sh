#!/usr/bin/env bash
# Call 1: the tank at rest as shipped, (D12) now at the boundary rows too (docs/DFSPH.md (D12), "At the
# boundary rows"): validate at 0.0125, 0.00625 and 0.003125 m after 1, 2 and 3 s of settling, averaged
# over 2 s; then the tank with --solver dfsph ten seconds at about 250k particles (the guard watching,
# and what the rows' term costs against call 4 of docs/perf/2026-11-30-h200-pressure-stabilisation/).
set -u
scripts/gpu/setup-and-build.sh ranryu > $OUT/build.txt 2>&1 || { tail -30 $OUT/build.txt; exit 1; }
. scripts/gpu/env.sh x
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | tee $OUT/device.txt; date -u | tee -a $OUT/device.txt
mkdir -p tankv seconds/250k
for settle in 1 2 3; do for dx in 0.0125 0.00625 0.003125; do
  s=$(date +%s)
  timeout 100 $B validate hydrostatic --solver dfsph --spacing $dx --settle $settle --average 2 --json tankv/s$settle-$dx.json --quiet > tankv/s$settle-$dx.txt 2>&1
  rc=$?
  f=tankv/s$settle-$dx.txt
  echo "== tank settle $settle dx $dx rc $rc $(( $(date +%s) - s )) s: $(grep -o 'interior (a kernel support from floor and surface): max [0-9.]*' $f | awk '{print $NF}') / $(grep -o 'floor layer: [0-9.]*' $f | awk '{print $NF}'), pair $(grep -o "floor's pair (the floor layer and the next): [0-9.]*" $f | awk '{print $NF}'), rms $(grep -o 'rms speed averaged over the 2 s: [0-9.]*' $f | awk '{print $NF}'); $(grep each $f); $(tail -1 $f)"
done; done 2>&1 | tee $OUT/tankv.txt
OUT=$PWD/seconds/250k SOLVER=dfsph PARTICLES=250000 SCENES="hydrostatic" RUN_TIMEOUT=220 scripts/gpu/scenes-seconds.sh 10 2>&1 | tee $OUT/seconds.txt
grep -hE "substeps/frame \(|density solve|^guard" seconds/250k/hydrostatic.txt | tee -a $OUT/seconds.txt
tar czf $OUT/call1.tgz tankv seconds
