#!/usr/bin/env bash
# Issue 11's side-by-side: the dam break's front at a/dx = 40 and 80 (free-slip and no-slip) and the
# tank at rest at 40 and 80 layers, with DFSPH and WCSPH, each run's steps and wall time, in one call.
scripts/gpu/setup-and-build.sh ranryu >/dev/null 2>&1 || { echo build failed; exit 1; }
. scripts/gpu/env.sh x
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $out/device.txt; date -u >> $out/device.txt
d=docs/perf/2026-11-29-h200-side-by-side-validation; [ -d $d ] || d=scratch/gpu3
mkdir -p $out/r
for s in dfsph wcsph; do
  for dx in 0.005 0.0025; do
    for walls in free noslip; do
      sc=""; [ $walls = noslip ] && sc="--scene $d/db-noslip.json"
      timeout 100 $B validate dam-break $sc --solver $s --spacing $dx --json $out/r/db-$s-$dx-$walls.json > $out/r/db-$s-$dx-$walls.txt 2>&1
      echo "== db $s $dx $walls rc $? $(grep -E 'rms' $out/r/db-$s-$dx-$walls.txt | tail -1) $(grep -E 'steps in' $out/r/db-$s-$dx-$walls.txt | tail -1)"
    done
  done
  for dx in 0.00625 0.003125; do
    timeout 100 $B validate hydrostatic --solver $s --spacing $dx --json $out/r/hs-$s-$dx.json > $out/r/hs-$s-$dx.txt 2>&1
    echo "== hs $s $dx rc $? $(grep -E '^pressure error|^floor layer' $out/r/hs-$s-$dx.txt | tr '\n' ' ') $(grep -E 'steps in' $out/r/hs-$s-$dx.txt | tail -1)"
  done
done
tar czf $out/r.tgz -C $out r && rm -rf $out/r
