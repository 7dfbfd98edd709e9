#!/usr/bin/env bash
# The density solve's bound eta against the spacing, with the plan two frames back: the dam break at
# 246k with eta = 0.05 % and at 1M with eta = 0.03 % (eta proportional to the spacing from 0.05 % at
# 0.00317 m gives 0.032 % at 0.002 m), ten simulated seconds each, particle shading at 640x360, the
# guard watching. The shipped 0.01 % at both: ../2026-11-28-h200-pair-list/call1/db-246k-10s-slots0.*
# and ../2026-11-28-h200-dfsph-10s/1m/dam-break.*.
scripts/gpu/setup-and-build.sh ranryu >/dev/null 2>&1 || { echo build failed; exit 1; }
. scripts/gpu/env.sh x
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $out/device.txt; date -u >> $out/device.txt
for run in "246k 0.00317 0.0005 80" "1m 0.002 0.0003 190"; do
  set -- $run
  python3 -c "import json; s=json.load(open('media/scenes/dam-break.json')); s['sph']['max_density_error']=$3; json.dump(s,open('$out/db-eta$3.json','w'))"
  timeout $4 $B profile --scene $out/db-eta$3.json --solver dfsph --spacing $2 --frames 600 --warmup 0 --shading particles --size 640x360 \
    --records $out/db-$1-eta$3.csv > $out/db-$1-eta$3.txt 2>&1
  echo "$1 eta $3 rc $?"; grep -E 'substeps/frame|density solve:|fps and|^guard|ranryu: simulation' $out/db-$1-eta$3.txt | grep -v 'profile: frame'
  tail -c 300 $out/db-$1-eta$3.txt | tr '\r' '\n' | tail -2
done
