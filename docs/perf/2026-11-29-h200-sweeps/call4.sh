#!/usr/bin/env bash
# The scene-settings rule now picks DFSPH for the drop (x2.5: sph.cfl 1.0; x2: 0.8, 177 against 176 GPU
# ms a simulated second, PBF's shipped 8x4 362): does it hold at about 250k and 1M particles for 10 s?
scripts/gpu/setup-and-build.sh ranryu >/dev/null 2>&1 || { echo build failed; exit 1; }
. scripts/gpu/env.sh x
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $out/device.txt; date -u >> $out/device.txt
for f in 2 2.5; do
  case $f in 2) keys="sph.cfl=0.8 sph.force_factor=0.5 sph.max_time_step=0.01";; 2.5) keys="sph.cfl=1.0 sph.force_factor=0.625 sph.max_time_step=0.0125";; esac
  for n in 250000 1000000; do
    mkdir -p $out/x$f-$n
    t0=$(date +%s)
    OUT=$out/x$f-$n SOLVER=dfsph PARTICLES=$n SCENES=drop KEYS="sph.solver=dfsph $keys" RUN_TIMEOUT=140 scripts/gpu/scenes-seconds.sh 10
    echo "   x$f $n: $(( $(date +%s) - t0 )) s; $(grep -E 'density solve|largest|most' $out/x$f-$n/drop.txt | head -3 | tr '\n' ' ')"
  done
done
tar czf $out/drop.tgz -C $out $(cd $out && ls -d x*) && rm -rf $out/x*
