#!/usr/bin/env bash
# name key=val ...
cd /work/main
name=$1; shift
python3 scripts/gpu/scene-at.py hydrostatic /tmp/tk/$name.json 30720 "$@" > /dev/null
build/rest/app/ranryu profile ${SHADERS:+--shader-dir $SHADERS} --scene /tmp/tk/$name.json --solver dfsph --spacing 0.00625 --frames ${FRAMES:-12} --warmup 0 --shading particles --size 64x36 --records /tmp/tk/$name.csv > /tmp/tk/$name.txt 2>&1
python3 - "$name" <<'PY'
import csv,sys
n=sys.argv[1]
rows=list(csv.DictReader(open(f'/tmp/tk/{n}.csv')))
print(n, 'maxv per frame:', ' '.join(f"{float(r['max_speed']):.2f}" for r in rows), '| it/step', round(sum(int(r['iterations']) for r in rows)/max(1,sum(int(r['substeps']) for r in rows)),1), 'sub/f', round(sum(int(r['substeps']) for r in rows)/len(rows),1))
PY
