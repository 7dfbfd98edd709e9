#!/usr/bin/env bash
# The rows in (D10) (271e7d2) at the finer spacings: the dam break's surge front at a/dx = 40 and 80
# with DFSPH, free-slip and no-slip; the tank at rest at three spacings averaged over 0.5 s and 2 s, as
# shipped and with the kernel-gradient correction (D11).
scripts/gpu/setup-and-build.sh ranryu >/dev/null 2>&1 || { echo build failed; exit 1; }
. scripts/gpu/env.sh x
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $out/device.txt; date -u >> $out/device.txt
d=docs/perf/2026-11-29-tank-floor/h200; mkdir -p $out/r
for dx in 0.005 0.0025; do
  for walls in free noslip; do
    sc=""; [ $walls = noslip ] && sc="--scene $d/db-noslip.json"
    t0=$(date +%s)
    timeout 120 $B validate dam-break $sc --solver dfsph --spacing $dx --json $out/r/db-$dx-$walls.json > $out/r/db-$dx-$walls.txt 2>&1
    echo "== db $dx $walls rc $? $(( $(date +%s) - t0 )) s"; grep -iE "rms|steps" $out/r/db-$dx-$walls.txt | tail -3
  done
done
for v in shipped gc; do
  sc=""; [ $v = gc ] && sc="--scene $d/hs-gc.json"
  for dx in 0.0125 0.00625 0.003125; do
    for av in 0.5 2; do
      t0=$(date +%s)
      timeout 150 $B validate hydrostatic $sc --solver dfsph --spacing $dx --average $av --json $out/r/hs-$v-$dx-$av.json > $out/r/hs-$v-$dx-$av.txt 2>&1
      echo "== hs $v $dx avg $av rc $? $(( $(date +%s) - t0 )) s"; grep -E "interior|floor layer|rms speed" $out/r/hs-$v-$dx-$av.txt
    done
  done
done
tar czf $out/r.tgz -C $out r && rm -rf $out/r
