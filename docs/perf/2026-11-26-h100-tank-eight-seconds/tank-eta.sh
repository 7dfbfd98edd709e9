#!/usr/bin/env bash
# The tank at rest with DFSPH over 8 s after 1 s: the scene, a tighter density solve, the complementarity error, both.
scripts/gpu/setup-and-build.sh ranryu >/dev/null 2>&1 || { echo build failed; exit 1; }
. scripts/gpu/env.sh x
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $out/device.txt; date -u >> $out/device.txt
mk() { out=$out python3 - "$@" <<'PY'
import json,sys,os
s=json.load(open('media/scenes/hydrostatic.json'))
for kv in sys.argv[2:]:
    k,v=kv.split('='); s['sph'][k]=json.loads(v)
json.dump(s,open(os.environ['out']+'/'+sys.argv[1]+'.json','w'))
PY
}
mk eta5 max_density_error=1e-5 max_iterations=1000
mk compl complementarity_error=true
mk both max_density_error=1e-5 max_iterations=1000 complementarity_error=true
for spec in 0.0125:eta5 0.0125:compl 0.0125:both 0.00625:compl 0.00625:eta5 0.00625:both 0.003125:compl; do
  dx=${spec%%:*}; v=${spec#*:}
  t0=$(date +%s)
  timeout 150 $B validate hydrostatic --scene $out/$v.json --solver dfsph --spacing $dx --average 8 --json $out/hs-$v-$dx.json --quiet > $out/hs-$v-$dx.txt 2>&1
  echo "== $v $dx rc $? $(( $(date +%s) - t0 )) s"; grep -E "^pressure error|^floor layer|^rms speed|steps in" $out/hs-$v-$dx.txt | cut -c1-200
done
cd $out && tar czf all.tgz *.txt *.json
