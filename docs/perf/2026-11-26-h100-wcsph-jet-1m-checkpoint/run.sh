#!/usr/bin/env bash
# WCSPH's turbulent jet at about 1M particles for 10 s in two calls (10-minute limit): A starts it and
# is stopped by SIGTERM before the call's end, writing a checkpoint; B resumes it to frame 600.
mode=$1; limit=${2:-540}
scripts/gpu/setup-and-build.sh ranryu >/dev/null 2>&1 || { echo build failed; exit 1; }
. scripts/gpu/env.sh x
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $out/device.txt; date -u >> $out/device.txt
ck=build/gpu/jet1m.ckpt
if [ "$mode" = A ]; then
  rm -f $ck
  dx=$(python3 scripts/gpu/scene-at.py turbulent-jet $out/jet.json 1000000)
  echo "spacing $dx"
  timeout -s TERM $limit $B profile --scene $out/jet.json --solver wcsph --spacing $dx --shading particles --size 640x360 \
    --frames 600 --warmup 0 --records $out/A.csv --checkpoint $ck > $out/A.txt 2>&1; echo "rc $?"
  tail -5 $out/A.txt
else
  timeout -s TERM $limit $B profile --resume $ck --shading particles --size 640x360 --frames ${FRAMES:-300} --warmup 0 \
    --records $out/B.csv --checkpoint build/gpu/jet1m-b.ckpt > $out/B.txt 2>&1; echo "rc $?"
  tail -30 $out/B.txt
fi
ls -la build/gpu/*.ckpt
python3 - $out/*.csv <<'PY'
import csv,sys
for f in sys.argv[1:]:
    rows=list(csv.DictReader(open(f)))
    if not rows: print(f,'empty'); continue
    print(f, 'frames', rows[0]['frame'], '..', rows[-1]['frame'], 't', rows[-1]['time'], 'substeps mean', sum(float(r['substeps']) for r in rows)/len(rows),
          'max rho', max(float(r['max_density']) for r in rows), 'max v', max(float(r['max_speed']) for r in rows))
PY
cd $out && tar czf all.tgz *.txt *.csv device.txt 2>/dev/null
