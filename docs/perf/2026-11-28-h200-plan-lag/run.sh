#!/usr/bin/env bash
# Is a run the same run however fast its records come back, with each frame planned from the record
# five frames back (commit c6e48a1's engine/sim/fluid.h planning_record(); two back since)? The dam break at ~246k with DFSPH
# and WCSPH: 60 frames of `profile`, 30 + a checkpoint + 30 resumed, and 60 frames of `record`
# (PNG writes slow the CPU side), each frame's record compared; the straight runs also against the
# H100's of 2026-11-26 (commit c8c3d12, which planned from the newest record at hand). Then the dam
# break's ten seconds at 246k with DFSPH and the whole pipeline at 1920x1080, for this device's figure.
scripts/gpu/setup-and-build.sh ranryu >/dev/null 2>&1 || { echo build failed; exit 1; }
. scripts/gpu/env.sh x
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $out/device.txt; date -u >> $out/device.txt
git_old=docs/perf/2026-11-26-h100-resume-vs-straight
dx=0.00317
for solver in dfsph wcsph; do
  o=$out/$solver; mkdir -p $o
  common=(--shading particles --size 320x180 --quiet)
  $B profile --scene dam-break --solver $solver --spacing $dx --frames 60 --warmup 0 --records $o/straight.csv "${common[@]}" > $o/straight.txt 2>&1
  $B profile --scene dam-break --solver $solver --spacing $dx --frames 30 --warmup 0 --records $o/first.csv --checkpoint $o/c.bin "${common[@]}" > $o/first.txt 2>&1
  $B profile --resume $o/c.bin --frames 30 --warmup 0 --records $o/resumed.csv "${common[@]}" > $o/resumed.txt 2>&1
  rm -f $o/c.bin
  $B record --scene dam-break --solver $solver --spacing $dx --frames 60 --out /tmp/rec-$solver --records $o/record.csv "${common[@]}" > $o/record.txt 2>&1
  python3 - $o $git_old/$solver/straight.csv <<'PY'
import csv,sys
o,old=sys.argv[1],sys.argv[2]
keys=('time','substeps','max_speed','max_density','iterations')
def rows(f): return {r['frame']:r for r in csv.DictReader(open(f))}
s=rows(o+'/straight.csv')
def first_diff(y):
    for f in sorted(y, key=int):
        if f in s and any(s[f][k]!=y[f][k] for k in keys if k in y[f]): return f
    return None
r=rows(o+'/resumed.csv'); r.update(rows(o+'/first.csv'))
print(o.split('/')[-1], 'first differing frame: resumed', first_diff(r), '| record', first_diff(rows(o+'/record.csv')),
      '| H100 c8c3d12 straight', first_diff(rows(old)), '| frames', len(s), len(r), 't', s[str(len(s)-1)]['time'])
PY
done
$B profile --scene dam-break --solver dfsph --spacing $dx --frames 600 --warmup 0 --size 1920x1080 --json $out/db-246k-10s.json --quiet > $out/db-246k-10s.txt 2>&1
tail -25 $out/db-246k-10s.txt
cd $out && tar czf all.tgz */*.csv */*.txt device.txt db-246k-10s.* && rm -rf dfsph wcsph
