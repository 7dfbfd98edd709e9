#!/usr/bin/env bash
# DFSPH's pair list (docs/DFSPH.md (D12)) against the walks it replaces, on one machine, one build:
# 1. the plan two frames back (the change of 2026-11-28 not yet run on a GPU): the dam break at 246k,
#    60 frames of DFSPH and of WCSPH with the list off, each frame's record against the H100's straight
#    runs of 2026-11-26 (commit c8c3d12, docs/perf/2026-11-26-h100-resume-vs-straight/), and DFSPH's
#    with the list on against its run with it off;
# 2. the dam break's ten seconds at 246k with DFSPH, the list off (sph.pair_slots 0) and on (64),
#    particle shading at 640x360, as docs/PERFORMANCE.md's ten-second tables;
# 3. the same at 1M particles for two simulated seconds (the surge and the impact).
scripts/gpu/setup-and-build.sh ranryu >/dev/null 2>&1 || { echo build failed; exit 1; }
. scripts/gpu/env.sh x
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $out/device.txt; date -u >> $out/device.txt; git rev-parse HEAD >> $out/device.txt
for k in 0 32 64; do
  python3 -c "import json,sys; s=json.load(open('media/scenes/dam-break.json')); s['sph']['pair_slots']=$k; json.dump(s,open('$out/db-slots$k.json','w'))"
done
old=docs/perf/2026-11-26-h100-resume-vs-straight
common=(--shading particles --size 320x180 --quiet)
$B profile --scene $out/db-slots0.json --solver dfsph --spacing 0.00317 --frames 60 --warmup 0 --records $out/lag2-dfsph.csv "${common[@]}" > $out/lag2-dfsph.txt 2>&1
$B profile --scene $out/db-slots64.json --solver dfsph --spacing 0.00317 --frames 60 --warmup 0 --records $out/lag2-dfsph-pairs.csv "${common[@]}" > $out/lag2-dfsph-pairs.txt 2>&1
$B profile --scene $out/db-slots0.json --solver wcsph --spacing 0.00317 --frames 60 --warmup 0 --records $out/lag2-wcsph.csv "${common[@]}" > $out/lag2-wcsph.txt 2>&1
python3 - $out $old <<'PY'
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
    print(s, 'lag 2 against the H100 c8c3d12 straight run: first differing frame', first_diff(a,h), 'of', len(a),
          '| substeps over the frames both ran', sum(int(a[f]['substeps']) for f in a if f in h), sum(int(h[f]['substeps']) for f in a if f in h))
print('dfsph, the list on against off: first differing frame', first_diff(rows(f'{out}/lag2-dfsph-pairs.csv'), rows(f'{out}/lag2-dfsph.csv')))
PY
for k in 0 64; do
  $B profile --scene $out/db-slots$k.json --solver dfsph --spacing 0.00317 --frames 600 --warmup 0 --shading particles --size 640x360 --records $out/db-246k-10s-slots$k.csv --quiet > $out/db-246k-10s-slots$k.txt 2>&1
  grep -E 'dfsph\.|substeps/frame|density solve|fps and|memory' $out/db-246k-10s-slots$k.txt | sed "s/^/246k slots $k: /"
done
for k in 0 64 32; do
  $B profile --scene $out/db-slots$k.json --solver dfsph --spacing 0.002 --frames 120 --warmup 0 --shading particles --size 640x360 --records $out/db-1m-2s-slots$k.csv --quiet > $out/db-1m-2s-slots$k.txt 2>&1
  grep -E 'dfsph\.|substeps/frame|density solve|fps and|memory' $out/db-1m-2s-slots$k.txt | sed "s/^/1M slots $k: /"
done
