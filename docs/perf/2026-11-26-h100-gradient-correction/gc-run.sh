#!/usr/bin/env bash
# (D11) experiment: the tank at rest with and without the gradient correction at three spacings; the dam break 246k for 3 s.
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
for dx in 0.0125 0.00625 0.003125; do
  for v in base gc gc1; do
    t0=$(date +%s)
    timeout 200 $B validate hydrostatic --scene $out/$v.json --solver dfsph --spacing $dx --json $out/hs-$v-$dx.json --quiet > $out/hs-$v-$dx.txt 2>&1
    echo "== $v $dx rc $? $(( $(date +%s) - t0 )) s"; grep -E "interior|floor layer|rms speed|steps in" $out/hs-$v-$dx.txt
  done
done
VARIANTS="dam-break/base: dam-break/gc:sph.gradient_correction=true drop/base: drop/gc:sph.gradient_correction=true" FRAMES=180 TAG=flow OUT=$out bash scratch/gpu-var.sh
cd $out && tar czf all.tgz *.txt *.json flow/*.txt flow/*.csv
