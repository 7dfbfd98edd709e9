#!/usr/bin/env bash
# Does a resumed run part from an unstopped one on the H100? DFSPH, WCSPH and PBF dam breaks at ~246k:
# 60 frames straight, and 30 + a checkpoint + 30 resumed; each frame's record compared.
scripts/gpu/setup-and-build.sh ranryu >/dev/null 2>&1 || { echo build failed; exit 1; }
. scripts/gpu/env.sh x
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $out/device.txt; date -u >> $out/device.txt
dx=0.00317
for solver in dfsph wcsph pbf; do
  o=$out/$solver; mkdir -p $o
  common=(--shading particles --size 320x180 --warmup 0 --quiet)
  $B profile --scene dam-break --solver $solver --spacing $dx --frames 60 --records $o/straight.csv "${common[@]}" > $o/straight.txt 2>&1
  $B profile --scene dam-break --solver $solver --spacing $dx --frames 60 --records $o/straight2.csv "${common[@]}" > $o/straight2.txt 2>&1
  $B profile --scene dam-break --solver $solver --spacing $dx --frames 30 --records $o/first.csv --checkpoint $o/c.bin "${common[@]}" > $o/first.txt 2>&1
  $B profile --resume $o/c.bin --frames 30 --records $o/resumed.csv "${common[@]}" > $o/resumed.txt 2>&1
  rm -f $o/c.bin
  python3 - $o <<'PY'
import csv,sys
o=sys.argv[1]
s=list(csv.DictReader(open(o+'/straight.csv'))); s2=list(csv.DictReader(open(o+'/straight2.csv')))
r=list(csv.DictReader(open(o+'/resumed.csv')))
def first_diff(x, y, start):
    for a in x[start:]:
        b=[z for z in y if z['frame']==a['frame']]
        if b and any(a[k]!=b[0][k] for k in ('time','substeps','max_speed','max_density')): return a['frame']
    return None
print(o.split('/')[-1], 'resumed against straight: first differing frame', first_diff(s, r, 30),
      '| straight against straight: first differing frame', first_diff(s, s2, 0),
      '| t', s[-1]['time'], s2[-1]['time'], r[-1]['time'])
PY
done
cd $out && tar czf all.tgz */*.csv */*.txt device.txt
