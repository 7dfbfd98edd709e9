#!/usr/bin/env bash
# Call 4: the drop and the turbulent jet with DFSPH for 10 s at about 250k as shipped and with the
# dam break's new bounds (eta 1e-3, eta_p 1e-2), then at about 1M with the new bounds.
T0=$(date +%s)
. scripts/gpu/env.sh call4
o=$out/call4; mkdir -p $o
{ nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; date -u; } | tee $o/device.txt
K="sph.max_density_error=1e-3 sph.max_particle_density_error=1e-2"
SOLVER=dfsph PARTICLES=250000 SCENES="drop turbulent-jet" RUN_TIMEOUT=100 OUT=$o/s250k-shipped scripts/gpu/scenes-seconds.sh 10
SOLVER=dfsph PARTICLES=250000 SCENES="drop turbulent-jet" RUN_TIMEOUT=100 KEYS="$K" OUT=$o/s250k-peak scripts/gpu/scenes-seconds.sh 10
echo "elapsed $(( $(date +%s)-T0 )) s"
SOLVER=dfsph PARTICLES=1000000 SCENES="drop turbulent-jet" RUN_TIMEOUT=$(( (500-($(date +%s)-T0))/2 )) KEYS="$K" OUT=$o/s1m-peak scripts/gpu/scenes-seconds.sh 10
echo "elapsed $(( $(date +%s)-T0 )) s"
tar czf $OUT/call4.tgz -C $out call4 && rm -rf $o
