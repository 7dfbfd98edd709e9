#!/usr/bin/env bash
# Call 4: the tank at rest as shipped with the pressure stabilisation (D12, sph.pressure_stabilisation
# 0.25 in media/scenes/hydrostatic.json): validate at 0.0125, 0.00625 and 0.003125 m after 1 and 2 s,
# averaged over 2 s; then the tank with --solver dfsph ten seconds at about 250k particles and two
# seconds at about 1M (its ten would take more than a call), the guard watching.
set -u
scripts/gpu/setup-and-build.sh ranryu > $OUT/build.txt 2>&1 || { tail -30 $OUT/build.txt; exit 1; }
. scripts/gpu/env.sh x
mkdir -p tankv seconds/250k seconds/1m
for settle in 1 2; do for dx in 0.0125 0.00625 0.003125; do
  s=$(date +%s)
  timeout 100 $B validate hydrostatic --solver dfsph --spacing $dx --settle $settle --average 2 --json tankv/s$settle-$dx.json --quiet > tankv/s$settle-$dx.txt 2>&1
  f=tankv/s$settle-$dx.txt
  echo "== tank settle $settle dx $dx rc $? $(( $(date +%s) - s )) s: $(grep -o 'interior (a kernel support from floor and surface): max [0-9.]*' $f | awk '{print $NF}') / $(grep -o 'floor layer: [0-9.]*' $f | awk '{print $NF}'), pair $(grep -o "floor's pair (the floor layer and the next): [0-9.]*" $f | awk '{print $NF}'), rms $(grep -o 'rms speed averaged over the 2 s: [0-9.]*' $f | awk '{print $NF}'); $(grep each $f); $(tail -1 $f)"
done; done 2>&1 | tee $OUT/tankv.txt
OUT=$PWD/seconds/250k SOLVER=dfsph PARTICLES=250000 SCENES="hydrostatic" RUN_TIMEOUT=200 scripts/gpu/scenes-seconds.sh 10 2>&1 | tee $OUT/seconds.txt
grep -hE "substeps/frame \(|density solve|^guard" seconds/250k/hydrostatic.txt | tee -a $OUT/seconds.txt
OUT=$PWD/seconds/1m SOLVER=dfsph PARTICLES=1000000 SCENES="hydrostatic" RUN_TIMEOUT=170 scripts/gpu/scenes-seconds.sh 2 2>&1 | tee -a $OUT/seconds.txt
grep -hE "substeps/frame \(|density solve|^guard" seconds/1m/hydrostatic.txt | tee -a $OUT/seconds.txt
tar czf $OUT/call4.tgz tankv seconds
