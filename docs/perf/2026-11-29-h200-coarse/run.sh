#!/usr/bin/env bash
# The density solve's coarse correction (docs/DFSPH.md (D12)) on the GPU: the dam break at 246k for ten
# simulated seconds without it (as shipped) and with it (sph.coarse_sweeps 40, which iterates plain
# relaxed Jacobi); the tank at rest at 246k for ten seconds with it (its scene's DFSPH settings); and
# `validate hydrostatic` with it at 0.00625 and 0.003125 m over two seconds after one. Particle shading
# at 640x360, the guard watching. Output: one tar under $OUT.
scripts/gpu/setup-and-build.sh ranryu >/dev/null 2>&1 || { echo build failed; exit 1; }
. scripts/gpu/env.sh x
r=$out/r; mkdir -p $r
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $r/device.txt; date -u >> $r/device.txt
keys() {   # scene file, output, python dict of "sph" keys
  python3 -c "import json; s=json.load(open('$1')); s['sph'].update($3); json.dump(s,open('$2','w'))"
}
keys media/scenes/dam-break.json $r/db-coarse.json "{'coarse_sweeps': 40}"
keys media/scenes/hydrostatic.json $r/hs-coarse.json "{'coarse_sweeps': 40}"
summary() { grep -E 'substeps/frame|density solve:|fps and|^guard|ranryu: simulation|coarse\.|pressure\.solve' $1 | grep -v 'profile: frame'; }
for run in "db-base media/scenes/dam-break.json 0.00317 100" "db-coarse $r/db-coarse.json 0.00317 130" "hs-coarse $r/hs-coarse.json 0.003125 170"; do
  set -- $run
  timeout $4 $B profile --scene $2 --solver dfsph --spacing $3 --frames 600 --warmup 0 --shading particles --size 640x360 \
    --records $r/$1.csv > $r/$1.txt 2>&1
  echo "== $1 rc $?"; summary $r/$1.txt; tail -c 300 $r/$1.txt | tr '\r' '\n' | tail -2
done
for dx in 0.00625 0.003125; do
  timeout 90 $B validate hydrostatic --scene $r/hs-coarse.json --solver dfsph --spacing $dx --average 2 --quiet --json $r/v-coarse-$dx.json > $r/v-coarse-$dx.txt 2>&1
  echo "== validate $dx rc $?"; grep -E 'pressure error in the interior|floor layer:|rms speed' $r/v-coarse-$dx.txt
done
tar czf $out/coarse.tgz -C $out r
