#!/usr/bin/env bash
# Call 2: the rows' compact term measured against the hydrostatic pressure's difference (row_hydrostatic(),
# glsl/sim/dfsph/dfsph.glsl), as shipped: validate at 0.0125, 0.00625 and 0.003125 m after 1 and 2 s,
# averaged over 2 s; the same with the fluid's compact term measured so too (the shaders in FG, a
# variant, --shader-dir); then the tank with --solver dfsph ten seconds at about 250k particles.
set -u
FG=${FG:-scratch/glsl-fg}
scripts/gpu/setup-and-build.sh ranryu > $OUT/build.txt 2>&1 || { tail -30 $OUT/build.txt; exit 1; }
. scripts/gpu/env.sh x
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | tee $OUT/device.txt; date -u | tee -a $OUT/device.txt
mkdir -p tankv seconds/250k
for variant in shipped fg; do for settle in 1 2; do for dx in 0.0125 0.00625 0.003125; do
  s=$(date +%s)
  extra=(); [ $variant = fg ] && extra=(--shader-dir "$FG")
  f=tankv/$variant-s$settle-$dx
  timeout 100 $B validate hydrostatic --solver dfsph --spacing $dx --settle $settle --average 2 --json $f.json --quiet "${extra[@]}" > $f.txt 2>&1
  rc=$?
  echo "== $variant settle $settle dx $dx rc $rc $(( $(date +%s) - s )) s: $(grep -o 'interior (a kernel support from floor and surface): max [0-9.]*' $f.txt | awk '{print $NF}') / $(grep -o 'floor layer: [0-9.]*' $f.txt | awk '{print $NF}'), pair $(grep -o "floor's pair (the floor layer and the next): [0-9.]*" $f.txt | awk '{print $NF}'), rms $(grep -o 'rms speed averaged over the 2 s: [0-9.]*' $f.txt | awk '{print $NF}'); $(grep each $f.txt | cut -c60-)"
done; done; done 2>&1 | tee $OUT/tankv.txt
OUT=$PWD/seconds/250k SOLVER=dfsph PARTICLES=250000 SCENES="hydrostatic" RUN_TIMEOUT=200 scripts/gpu/scenes-seconds.sh 10 2>&1 | tee $OUT/seconds.txt
grep -hE "substeps/frame \(|density solve|^guard" seconds/250k/hydrostatic.txt | tee -a $OUT/seconds.txt
tar czf $OUT/call2.tgz tankv seconds
