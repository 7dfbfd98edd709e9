#!/usr/bin/env bash
# Call 3: the dam break as it now ships (eta 1e-3, eta_p 1e-2) for 10 s at 250k and 1M, then the
# surge front at a/dx = 40 and 80 with the scene as it now ships and as it shipped before.
T0=$(date +%s)
. scripts/gpu/env.sh call3
o=$out/call3; mkdir -p $o
{ nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; date -u; git log -1 --format=%H; } | tee $o/device.txt
SOLVER=dfsph PARTICLES=250000 SCENES=dam-break RUN_TIMEOUT=120 OUT=$o/s250k scripts/gpu/scenes-seconds.sh 10
SOLVER=dfsph PARTICLES=1000000 SCENES=dam-break RUN_TIMEOUT=220 OUT=$o/s1m scripts/gpu/scenes-seconds.sh 10
echo "elapsed $(( $(date +%s)-T0 )) s"
for dx in 0.005 0.0025; do
  for v in now before; do
    f=media/scenes/dam-break.json; [ $v = before ] && f=scratch/scenes/dam-break-before.json
    [ $(( $(date +%s)-T0 )) -gt 480 ] && { echo "skipped front $dx $v (time)"; continue; }
    s=$(date +%s)
    timeout 150 $B validate dam-break --scene $f --solver dfsph --spacing $dx --json $o/front-$dx-$v.json --quiet > $o/front-$dx-$v.txt 2>&1
    echo "== front at $dx, $v: rc $?, $(( $(date +%s)-s )) s: $(grep -m1 'surge front error' $o/front-$dx-$v.txt)"
  done
done
echo "elapsed $(( $(date +%s)-T0 )) s"
tar czf $OUT/call3.tgz -C $out call3
