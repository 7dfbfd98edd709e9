#!/usr/bin/env bash
# (D11) experiment 2: the tank at rest, base / gc / gc1, three spacings, settled 1 s, averaged 3 s in half-second windows.
scripts/gpu/setup-and-build.sh ranryu >/dev/null 2>&1 || { echo build failed; exit 1; }
. scripts/gpu/env.sh x
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $out/device.txt; date -u >> $out/device.txt; git log -1 --format=%h >> $out/device.txt
mk() { python3 - "$@" <<'PY'
import json,sys
s=json.load(open('media/scenes/hydrostatic.json'))
for kv in sys.argv[2:]:
    k,v=kv.split('='); s['sph'][k]=json.loads(v)
json.dump(s,open(sys.argv[1],'w'))
PY
}
mk $out/base.json
mk $out/gc.json gradient_correction=true
mk $out/gc1.json gradient_correction=true warm_start=1
mk $out/base1.json warm_start=1
for dx in 0.0125 0.00625 0.003125; do
  for v in base gc gc1 base1; do
    t0=$(date +%s)
    timeout 200 $B validate hydrostatic --scene $out/$v.json --solver dfsph --spacing $dx --average 3 --json $out/hs-$v-$dx.json --quiet > $out/hs-$v-$dx.txt 2>&1
    echo "== $v $dx rc $? $(( $(date +%s) - t0 )) s"; grep -E "^pressure error|^floor layer|^rms speed|each half" $out/hs-$v-$dx.txt | cut -c1-400
  done
done
cd $out && tar czf all.tgz *.txt *.json
