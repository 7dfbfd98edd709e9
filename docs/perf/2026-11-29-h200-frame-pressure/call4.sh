#!/usr/bin/env bash
# The tank at rest: the boundary rows keeping their whole kappa_b as the warm start (rowsw1/: w = 1 for
# the rows, the fluid keeping the scene's 0.75) and the divergence solve from no pressure
# (sph.divergence_warm_start 0), at 0.003125, 0.00625 and 0.0125 m.
scripts/gpu/setup-and-build.sh ranryu >/dev/null 2>&1 || { echo build failed; exit 1; }
. scripts/gpu/env.sh x
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $out/device.txt; date -u >> $out/device.txt
mkdir -p $out/v
variant() {  # name dx "key=value ..." [extra validate args]
  local name=$1 dx=$2 keys=$3; shift 3
  python3 - "$out/v/$name.scene.json" $keys <<'PY'
import json, sys
s = json.load(open('media/scenes/hydrostatic.json'))
for kv in sys.argv[2:]:
    k, v = kv.split('=')
    s['sph'][k] = json.loads(v)
json.dump(s, open(sys.argv[1], 'w'))
PY
  t0=$(date +%s)
  timeout 120 $B validate hydrostatic --scene $out/v/$name.scene.json --solver dfsph --spacing $dx --json $out/v/$name.json "$@" > $out/v/$name.txt 2>&1
  echo "== $name ($dx; $keys $*) rc $? $(( $(date +%s) - t0 )) s"
  grep -E "interior|floor layer|rms speed|steps in" $out/v/$name.txt | sed 's/^/   /'
  grep -E "^ +0\.[0-9]+ +[0-9-]" $out/v/$name.txt | head -6 | awk '{printf "   z %s p %s ref %s (%+.2f %%)\n", $1, $2, $3, 100*($2-$3)/2452.5}'
}
for dx in 0.003125 0.00625 0.0125; do
  variant rowsw1-$dx $dx "" --shader-dir scratch/rowsw1
done
for dx in 0.003125 0.00625; do
  variant dws0-$dx $dx "divergence_warm_start=0"
done
variant rowsw1-dws0-0.003125 0.003125 "divergence_warm_start=0" --shader-dir scratch/rowsw1
tar czf $out/v.tgz -C $out v && rm -rf $out/v
