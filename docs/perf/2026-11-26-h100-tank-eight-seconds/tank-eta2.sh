#!/usr/bin/env bash
# The tank at rest with DFSPH at 0.00625 m over 8 s after 1 s with a density solve at eta = 1e-5.
scripts/gpu/setup-and-build.sh ranryu >/dev/null 2>&1 || { echo build failed; exit 1; }
. scripts/gpu/env.sh x
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $out/device.txt; date -u >> $out/device.txt
out=$out python3 - <<'PY'
import json,os
s=json.load(open('media/scenes/hydrostatic.json'))
s['sph']['max_density_error']=1e-5; s['sph']['max_iterations']=1000
json.dump(s,open(os.environ['out']+'/eta5.json','w'))
PY
t0=$(date +%s)
timeout 540 $B validate hydrostatic --scene $out/eta5.json --solver dfsph --spacing 0.00625 --average 8 --json $out/hs-eta5-0.00625.json --quiet > $out/hs-eta5-0.00625.txt 2>&1
echo "== eta5 0.00625 rc $? $(( $(date +%s) - t0 )) s"; grep -E "^pressure error|^floor layer|^rms speed|steps in|each half" $out/hs-eta5-0.00625.txt | cut -c1-600
cd $out && tar czf all.tgz *.txt *.json
