#!/usr/bin/env bash
# The scene-settings rule picks DFSPH x2 for the dam break at its own spacing (sph.dfsph_cfl 1.0, 198
# GPU ms a simulated second against the shipped x1's 282): the dam break at x2 and x1.5 at about 250k
# and 1M particles for 10 s.
scripts/gpu/setup-and-build.sh ranryu >/dev/null 2>&1 || { echo build failed; exit 1; }
. scripts/gpu/env.sh x
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $out/device.txt; date -u >> $out/device.txt
for f in 2 1.5; do
  case $f in 2) keys="sph.dfsph_cfl=1.0 sph.force_factor=0.5 sph.max_time_step=0.01";; 1.5) keys="sph.dfsph_cfl=0.75 sph.force_factor=0.375 sph.max_time_step=0.0075";; esac
  for n in 250000 1000000; do
    mkdir -p $out/x$f-$n
    t0=$(date +%s)
    OUT=$out/x$f-$n SOLVER=dfsph PARTICLES=$n SCENES=dam-break KEYS="$keys" RUN_TIMEOUT=110 scripts/gpu/scenes-seconds.sh 10 | cut -c1-300
    echo "   x$f $n: $(( $(date +%s) - t0 )) s"
  done
done
tar czf $out/db.tgz -C $out $(cd $out && ls -d x*) && rm -rf $out/x*
