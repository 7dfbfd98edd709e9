#!/usr/bin/env bash
# Second call (the first's report lost its 246k and lag-2 lines to the output's tail): the plan two
# frames back against the H100's c8c3d12 records, the list on against off at 246k over ten seconds, and
# DFSPH's other bundled scenes at about 250k particles for ten seconds with the plan two back (the
# dam break's is the first call's db-246k-10s-slots0). Everything under $OUT/all.tgz; short lines printed.
scripts/gpu/setup-and-build.sh ranryu >/dev/null 2>&1 || { echo build failed; exit 1; }
. scripts/gpu/env.sh x
w=$out/work; mkdir -p $w
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $w/device.txt; date -u >> $w/device.txt; git rev-parse HEAD >> $w/device.txt
cat $w/device.txt
for k in 0 64; do
  python3 -c "import json,sys; s=json.load(open('media/scenes/dam-break.json')); s['sph']['pair_slots']=$k; json.dump(s,open('$w/db-slots$k.json','w'))"
done
old=docs/perf/2026-11-26-h100-resume-vs-straight
common=(--shading particles --size 320x180 --quiet)
$B profile --scene $w/db-slots0.json --solver dfsph --spacing 0.00317 --frames 60 --warmup 0 --records $w/lag2-dfsph.csv "${common[@]}" > $w/lag2-dfsph.txt 2>&1
$B profile --scene $w/db-slots64.json --solver dfsph --spacing 0.00317 --frames 60 --warmup 0 --records $w/lag2-dfsph-pairs.csv "${common[@]}" > $w/lag2-dfsph-pairs.txt 2>&1
$B profile --scene $w/db-slots0.json --solver wcsph --spacing 0.00317 --frames 60 --warmup 0 --records $w/lag2-wcsph.csv "${common[@]}" > $w/lag2-wcsph.txt 2>&1
python3 - $w $old <<'PY'
import csv,sys
out,old=sys.argv[1],sys.argv[2]
keys=('time','substeps','max_speed','max_density','iterations')
def rows(f): return {r['frame']:r for r in csv.DictReader(open(f))}
def first_diff(a,b):
    for f in sorted(a, key=int):
        if f in b and any(a[f][k]!=b[f][k] for k in keys if k in b[f]): return f
    return None
for s in ('dfsph','wcsph'):
    a=rows(f'{out}/lag2-{s}.csv'); h=rows(f'{old}/{s}/straight.csv')
    both=[f for f in a if f in h]
    print(s, 'lag 2 against the H100 c8c3d12 straight run: first differing frame', first_diff(a,h), 'of', len(both),
          '| substeps over those frames', sum(int(a[f]['substeps']) for f in both), 'against', sum(int(h[f]['substeps']) for f in both))
print('dfsph, the list on against off: first differing frame', first_diff(rows(f'{out}/lag2-dfsph-pairs.csv'), rows(f'{out}/lag2-dfsph.csv')))
PY
$B profile --scene $w/db-slots64.json --solver dfsph --spacing 0.00317 --frames 600 --warmup 0 --shading particles --size 640x360 --records $w/db-246k-10s-slots64.csv --quiet > $w/db-246k-10s-slots64.txt 2>&1
grep -E '^(dfsph|frame)|substeps/frame|density solve:|fps and|device memory' $w/db-246k-10s-slots64.txt | sed "s/^/246k slots 64: /"
OUT=$w/scenes SOLVER=dfsph PARTICLES=250000 SCENES="drop turbulent-jet hydrostatic" scripts/gpu/scenes-seconds.sh 10
for f in $w/scenes/*.txt; do grep -E 'substeps/frame|density solve:|fps and' $f | sed "s|^|$(basename $f .txt): |"; done
cd $w && tar czf $out/all.tgz . && cd - >/dev/null && rm -rf $w
