#!/usr/bin/env bash
# The tank at rest as committed with (D11) on, DFSPH, 10 s at its own spacing, ~250k and ~1M.
scripts/gpu/setup-and-build.sh ranryu >/dev/null 2>&1 || { echo build failed; exit 1; }
. scripts/gpu/env.sh x
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $out/device.txt; date -u >> $out/device.txt
timeout 40 $B profile --scene media/scenes/hydrostatic.json --solver dfsph --frames 600 --warmup 0 --shading particles --size 640x360 --records $out/own.csv > $out/own.txt 2>&1
echo "own rc $?: $(grep -m1 -E 'fps and real-time|^ranryu: simulation' $out/own.txt)"; grep -h "^guard:" $out/own.txt
OUT=$out/t250 SOLVER=dfsph PARTICLES=250000 SCENES=hydrostatic RUN_TIMEOUT=140 scripts/gpu/scenes-seconds.sh 10
OUT=$out/t1m SOLVER=dfsph PARTICLES=1000000 SCENES=hydrostatic RUN_TIMEOUT=400 scripts/gpu/scenes-seconds.sh 10
for f in $out/own.csv $out/t250/hydrostatic.csv $out/t1m/hydrostatic.csv; do python3 - $f <<'PY'
import csv,sys
r=list(csv.DictReader(open(sys.argv[1])))
print(sys.argv[1], len(r), 'frames t=%s'%r[-1]['time'], 'maxv %.2f'%max(float(x['max_speed']) for x in r), 'maxrho %.3f'%max(float(x['max_density']) for x in r), 'substeps %.1f'%(sum(float(x['substeps']) for x in r)/len(r)))
PY
done
cd $out && tar czf all.tgz *.txt *.csv t250 t1m
