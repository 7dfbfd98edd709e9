#!/usr/bin/env bash
# The tank at rest at 0.003125 m (and 0.00625 m): what its floor's alternating layers (+5.6 / -3.5 /
# +2.1 % of rho0 g H in call 1) follow. Variants of the bundled scene's sph keys, one run each.
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
variant base 0.003125 ""
variant ws0 0.003125 "warm_start=0 divergence_warm_start=0"
variant ws05 0.003125 "warm_start=0.5"
variant div5 0.003125 "max_divergence_error=1e-5"
variant eta5 0.003125 "max_density_error=1e-5"
variant settle2 0.003125 "" --settle 2
variant ws0-00625 0.00625 "warm_start=0 divergence_warm_start=0"
variant base-00625 0.00625 ""
tar czf $out/v.tgz -C $out v && rm -rf $out/v
