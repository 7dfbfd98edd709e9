#!/usr/bin/env bash
# Passes within passes (engine/profile/gpu_timer.h; `ranryu profile --detail`), on the H200:
# 1. the dam break as shipped at 246k for ten seconds, the whole pipeline at 1920x1080, detail off: each
#    solve dispatch now opens a debug group of its own; its records must equal the last run's
#    (docs/perf/2026-12-01-h200-eliminated-rows/call2/dam-246k-1080p.csv) and its frame rate the 29.0 fps there;
# 2. the same with --detail: every dispatch within a solve, the rows' sizing, the surface's and the
#    raster's small passes timed apart, and what their timestamps cost;
# 3. the tank at rest at 246k (the rows eliminated, (D13)) for two seconds with --detail: its two row passes;
# 4. a lead: the dam break at 246k for ten seconds with the rows eliminated as the tank has them
#    (sph.eliminate_boundary_rows=true), the whole pipeline at 1920x1080.
set -u
scripts/gpu/setup-and-build.sh ranryu > $OUT/build.txt 2>&1 || { tail -30 $OUT/build.txt; exit 1; }
rm -f $OUT/build.txt   # the device returns at most eight files
. scripts/gpu/env.sh x
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | tee $OUT/device.txt; date -u | tee -a $OUT/device.txt
pat="substeps/frame \(|density solve:|divergence solve:|fps and real|^ *dfsph\.|^frame |^timed within|^ranryu: "
f=$OUT/dam-246k
timeout 100 $B profile --scene dam-break --spacing 0.00317 --size 1920x1080 --frames 600 --warmup 0 --records $f.csv > $f.txt 2>&1
echo "== 1. dam break 246k rc $?"; grep -E "$pat" $f.txt | cut -c1-400
cmp -s $f.csv docs/perf/2026-12-01-h200-eliminated-rows/call2/dam-246k-1080p.csv && echo "records: equal to the last run's" \
  || { echo "records differ from the last run's:"; diff <(cut -d, -f1-20 $f.csv) <(cut -d, -f1-20 docs/perf/2026-12-01-h200-eliminated-rows/call2/dam-246k-1080p.csv) | head -6; }
f=$OUT/dam-246k-detail
timeout 150 $B profile --scene dam-break --spacing 0.00317 --size 1920x1080 --frames 600 --warmup 0 --detail --records $f.csv > $f.txt 2>&1
echo "== 2. dam break 246k --detail rc $?"; sed -n '/^pass /,/^frame /p' $f.txt; grep -E "fps and real" $f.txt
cmp -s $f.csv $OUT/dam-246k.csv && echo "records: equal to run 1's" || echo "records differ from run 1's"
rm -f $f.csv
dx=$(python3 scripts/gpu/scene-at.py hydrostatic /tmp/tank.json 250000)
f=$OUT/tank-246k-detail
timeout 120 $B profile --scene /tmp/tank.json --solver dfsph --spacing $dx --shading particles --size 640x360 --frames 120 --warmup 0 --detail > $f.txt 2>&1
echo "== 3. tank 246k two seconds --detail rc $?"; grep -E "$pat" $f.txt | cut -c1-300
python3 scripts/gpu/scene-at.py dam-break /tmp/dam-elim.json 246078 sph.eliminate_boundary_rows=true > /dev/null
f=$OUT/dam-246k-eliminated
timeout 150 $B profile --scene /tmp/dam-elim.json --spacing 0.00317 --size 1920x1080 --frames 600 --warmup 0 --records $f.csv > $f.txt 2>&1
echo "== 4. dam break 246k, rows eliminated, rc $?"; grep -E "$pat|guard" $f.txt | grep -v "why its" | cut -c1-300
