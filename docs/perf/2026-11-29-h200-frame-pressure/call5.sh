#!/usr/bin/env bash
# The boundary rows accelerated with the fluid's Chebyshev weights ((D10) on kappa_b too, the tree of
# this call: correct_pressure.comp, kappa_previous_ n + nb floats): the tank at rest at three spacings
# (against call 1's), then the dam break as shipped for ten seconds at 246k and 1M particles.
scripts/gpu/setup-and-build.sh ranryu >/dev/null 2>&1 || { echo build failed; exit 1; }
. scripts/gpu/env.sh x
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $out/device.txt; date -u >> $out/device.txt
mkdir -p $out/hs
for dx in 0.0125 0.00625 0.003125; do
  t0=$(date +%s)
  timeout 150 $B validate hydrostatic --solver dfsph --spacing $dx --json $out/hs/hs-$dx.json > $out/hs/hs-$dx.txt 2>&1
  echo "== $dx rc $? $(( $(date +%s) - t0 )) s"; grep -E "interior|floor layer|rms speed|steps in" $out/hs/hs-$dx.txt
  grep -E "^ +0\.[0-9]+ +[0-9-]" $out/hs/hs-$dx.txt | head -4 | awk '{printf "   z %s p %s ref %s (%+.2f %%)\n", $1, $2, $3, 100*($2-$3)/2452.5}'
done
tar czf $out/hs.tgz -C $out hs && rm -rf $out/hs
TAG=db NS="250000 1000000" ETAS=1e-3 RUN_TIMEOUT=170 scripts/gpu/dfsph-eta.sh 2>&1 | grep -v "why its settings"
