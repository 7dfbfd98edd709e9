#!/usr/bin/env bash
# The drop at about 250k and 1M for 10 s: DFSPH at the sweep's x1.5 (sph.cfl 0.6) and PBF as shipped
# (8x4 scaled), after x2 and x2.5 stopped at both sizes (call 4).
scripts/gpu/setup-and-build.sh ranryu >/dev/null 2>&1 || { echo build failed; exit 1; }
. scripts/gpu/env.sh x
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $out/device.txt; date -u >> $out/device.txt
for v in x1.5 pbf; do
  for n in 250000 1000000; do
    mkdir -p $out/$v-$n
    t0=$(date +%s)
    if [ $v = pbf ]; then
      OUT=$out/$v-$n SOLVER=pbf PARTICLES=$n SCENES=drop RUN_TIMEOUT=150 scripts/gpu/scenes-seconds.sh 10
    else
      OUT=$out/$v-$n SOLVER=dfsph PARTICLES=$n SCENES=drop KEYS="sph.solver=dfsph sph.cfl=0.6 sph.force_factor=0.375 sph.max_time_step=0.0075" RUN_TIMEOUT=150 scripts/gpu/scenes-seconds.sh 10
    fi
    echo "   $v $n: $(( $(date +%s) - t0 )) s; $(grep -E 'substeps/frame \(|largest|fps and' $out/$v-$n/drop.txt | head -3 | tr '\n' ' ')"
  done
done
tar czf $out/drop.tgz -C $out $(cd $out && ls -d x* pbf*) && rm -rf $out/x* $out/pbf-*
