#!/usr/bin/env bash
# The tank at rest with DFSPH, with (D11) (as shipped) and without, three spacings, settled 1 s, averaged 8 s.
scripts/gpu/setup-and-build.sh ranryu >/dev/null 2>&1 || { echo build failed; exit 1; }
. scripts/gpu/env.sh x
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $out/device.txt; date -u >> $out/device.txt; git log -1 --format=%h >> $out/device.txt
out=$out python3 - <<'PY'
import json,os
s=json.load(open('media/scenes/hydrostatic.json'))
json.dump(s,open(os.environ['out']+'/gc.json','w'))
s['sph']['gradient_correction']=False
json.dump(s,open(os.environ['out']+'/base.json','w'))
PY
for dx in 0.0125 0.00625 0.003125; do
  for v in gc base; do
    t0=$(date +%s)
    timeout 200 $B validate hydrostatic --scene $out/$v.json --solver dfsph --spacing $dx --average 8 --json $out/hs-$v-$dx.json --quiet > $out/hs-$v-$dx.txt 2>&1
    echo "== $v $dx rc $? $(( $(date +%s) - t0 )) s"; grep -E "^pressure error|^floor layer|^rms speed" $out/hs-$v-$dx.txt | cut -c1-200
  done
done
cd $out && tar czf all.tgz *.txt *.json
