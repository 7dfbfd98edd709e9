#!/usr/bin/env bash
# 1. The dam break as shipped at 246k, the whole pipeline at 1920x1080 for ten seconds, as "Where it
#    stands" ran it (docs/perf/2026-11-30-h200-visits-from-hits/call2.sh): the change must leave the flows
#    (no eliminated rows) as they were. 2. time-rows.patch (a diagnostic, not shipped: the rows' two passes
#    each under a timer of its own), then the tank at 246k for two seconds with the rows eliminated (as
#    shipped) and with (D9)'s rows (sph.eliminate_boundary_rows=false), to see where the iteration's cost goes.
set -u
scripts/gpu/setup-and-build.sh ranryu > $OUT/build.txt 2>&1 || { tail -30 $OUT/build.txt; exit 1; }
. scripts/gpu/env.sh x
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | tee $OUT/device.txt; date -u | tee -a $OUT/device.txt
pat="substeps/frame \(|density solve:|fps and real|^dfsph\.|^frame "
f=$OUT/dam-246k-1080p
timeout 100 $B profile --scene dam-break --spacing 0.00317 --size 1920x1080 --frames 600 --warmup 0 --records $f.csv > $f.txt 2>&1
echo "== dam break 246k rc $?"; grep -E "$pat" $f.txt | cut -c1-200
git apply docs/perf/2026-12-01-h200-eliminated-rows/time-rows.patch || exit 1
scripts/gpu/setup-and-build.sh ranryu > $OUT/build2.txt 2>&1 || { tail -30 $OUT/build2.txt; exit 1; }
for v in on off; do
  dx=$(python3 scripts/gpu/scene-at.py hydrostatic /tmp/t-$v.json 250000 sph.eliminate_boundary_rows=$([ $v = on ] && echo true || echo false))
  f=$OUT/tank-$v
  timeout 120 $B profile --scene /tmp/t-$v.json --solver dfsph --spacing $dx --shading particles --size 640x360 --frames 120 --warmup 0 > $f.txt 2>&1
  echo "== tank rows eliminated $v rc $?"; grep -E "$pat" $f.txt | cut -c1-200
done
