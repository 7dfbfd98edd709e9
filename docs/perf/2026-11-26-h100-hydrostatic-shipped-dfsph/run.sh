#!/usr/bin/env bash
# The tank at rest with DFSPH as the scene sets it (w = 0.75, (D10) 0.98, the boundary rows), three spacings.
scripts/gpu/setup-and-build.sh ranryu >/dev/null 2>&1 || { echo build failed; exit 1; }
. scripts/gpu/env.sh x
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $out/device.txt; date -u >> $out/device.txt
for dx in 0.0125 0.00625 0.003125; do
  t0=$(date +%s)
  timeout 300 $B validate hydrostatic --solver dfsph --spacing $dx --json $out/hs-$dx.json --quiet > $out/hs-$dx.txt 2>&1
  echo "== $dx rc $? $(( $(date +%s) - t0 )) s"; grep -E "interior|floor layer|rms speed|steps in" $out/hs-$dx.txt
done
cd $out && tar czf all.tgz *.txt *.json
