#!/usr/bin/env bash
# The complementarity error (sph.complementarity_error) against the excess-only
# error: the tank at rest at two spacings (rows), the 1M tank's first frames (rows), the dam break at 246k for 10 s.
# Run on the GPU host from the repository root after scripts/gpu/setup-and-build.sh, with OUT set.
. scripts/gpu/env.sh x
mkdir -p scratch
python3 - <<'PY'   # the tank at rest with the boundary rows, and with the complementarity error too
import json
s = json.load(open('media/scenes/hydrostatic.json'))
s['sph']['boundary_rows'] = True
json.dump(s, open('scratch/h-rows.json', 'w'))
s['sph']['complementarity_error'] = True
json.dump(s, open('scratch/h-rows-c.json', 'w'))
PY
o=$OUT/c; mkdir -p $o
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | tee $o/device.txt; date -u | tee -a $o/device.txt
git rev-parse HEAD >> $o/device.txt; git diff --stat >> $o/device.txt
for dx in 0.00625 0.003125; do
  for v in rows rows-c; do
    s=$(date +%s)
    timeout 150 $B validate hydrostatic --scene scratch/h-$v.json --solver dfsph --spacing $dx > $o/h-$v-$dx.txt 2>&1
    echo "== hydrostatic $v $dx: rc $? $(( $(date +%s) - s )) s"; tail -n 4 $o/h-$v-$dx.txt
  done
done
OUT=$o VARIANTS="rowsc:sph.boundary_rows=true,sph.complementarity_error=true" PARTICLES=1000000 FRAMES=24 RUN_TIMEOUT=200 scripts/gpu/tank-fast.sh
for f in $o/tank-fast/*.txt; do echo "== $f"; grep -E "^exit|frame|fastest" $f | head -20; done
python3 - $o/tank-fast/rowsc-1000000.csv <<'PY'
import csv,sys
for r in csv.DictReader(open(sys.argv[1])): print(r['frame'], r['time'][:6], r['substeps'], r['iterations'], r['max_speed'][:6], r['max_density'][:6])
PY
OUT=$o TAG=c NS=250000 ETAS=1e-4 KEYS="sph.complementarity_error=true" RUN_TIMEOUT=150 scripts/gpu/dfsph-eta.sh 2>&1 | sed 's/^/c /'
mv $o/eta $o/eta-c
OUT=$o TAG=base NS=250000 ETAS=1e-4 RUN_TIMEOUT=150 scripts/gpu/dfsph-eta.sh 2>&1 | sed 's/^/base /'
cd $OUT && tar czf c.tgz c && rm -rf c
