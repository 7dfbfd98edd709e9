#!/usr/bin/env bash
# Call 2: the tank at rest with --solver dfsph for ten seconds at about 1M particles (owed since the
# 4 ms step cap), then the tank's validate at three spacings after 1 and 2 s of settling, averaged over 2 s
# (the shaders as committed), for the floor layer's scatter on this device.
set -u
scripts/gpu/setup-and-build.sh ranryu > $OUT/build.txt 2>&1 || { tail -30 $OUT/build.txt; exit 1; }
. scripts/gpu/env.sh x
mkdir -p tank1m tankv
OUT=$PWD/tank1m SOLVER=dfsph PARTICLES=1000000 SCENES="hydrostatic" RUN_TIMEOUT=440 scripts/gpu/scenes-seconds.sh 10 2>&1 | tee $OUT/tank1m.txt
grep -hE "substeps/frame \(|density solve|divergence solve|fps and real-time|^guard" tank1m/hydrostatic.txt | tee -a $OUT/tank1m.txt
for settle in 1 2; do for dx in 0.0125 0.00625 0.003125; do
  s=$(date +%s)
  timeout 60 $B validate hydrostatic --solver dfsph --spacing $dx --settle $settle --average 2 --json tankv/s$settle-$dx.json --quiet > tankv/s$settle-$dx.txt 2>&1
  echo "== tank settle $settle dx $dx rc $? $(( $(date +%s) - s )) s: $(grep -o 'interior (a kernel support from floor and surface): max [0-9.]*' tankv/s$settle-$dx.txt | awk '{print $NF}') / $(grep -o 'floor layer: [0-9.]*' tankv/s$settle-$dx.txt | awk '{print $NF}'), pair $(grep -o "floor's pair (the floor layer and the next): [0-9.]*" tankv/s$settle-$dx.txt | awk '{print $NF}')"
done; done 2>&1 | tee $OUT/tankv.txt
tar czf $OUT/tank.tgz tank1m tankv
