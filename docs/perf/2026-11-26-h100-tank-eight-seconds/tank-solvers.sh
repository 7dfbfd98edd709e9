#!/usr/bin/env bash
# The tank at rest over 8 s after 1 s with WCSPH and with PBF (as shipped), two spacings.
scripts/gpu/setup-and-build.sh ranryu >/dev/null 2>&1 || { echo build failed; exit 1; }
. scripts/gpu/env.sh x
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $out/device.txt; date -u >> $out/device.txt
for spec in wcsph:0.0125 pbf:0.0125 wcsph:0.00625 pbf:0.00625; do
  s=${spec%%:*}; dx=${spec#*:}
  t0=$(date +%s)
  timeout 200 $B validate hydrostatic --solver $s --spacing $dx --average 8 --json $out/hs-$s-$dx.json --quiet > $out/hs-$s-$dx.txt 2>&1
  echo "== $s $dx rc $? $(( $(date +%s) - t0 )) s"; grep -E "^pressure error|^floor layer|^rms speed|^interior over pairs|steps in" $out/hs-$s-$dx.txt | cut -c1-200
done
cd $out && tar czf all.tgz *.txt *.json
