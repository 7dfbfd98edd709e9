#!/usr/bin/env bash
# Call 1 (2026-12-02): the iteration caps at 1.1x + 1 (RANRYU_DFSPH_CAP=1.1,1) against the shipped
# 1.5x + 2, whose runs on this trajectory are call 1 of ../2026-12-02-wall-gradient (the tree of 2a65106:
# its records equal this tree's, whose later changes alter no arithmetic of the simulation).
# 1. the GL suite on the H200 (the impostors' compute raster's first run of it there);
# 2. with the rule: the dam break as shipped for ten seconds at 246,078 with the whole pipeline at
#    1920x1080 (issue 11's measure) and at 1M with particles at 640x360; the drop and the jet with
#    --solver dfsph at about 250k and 1M, the guard watching.
set -u
scripts/gpu/setup-and-build.sh all > /tmp/b.txt 2>&1 || { tail -30 /tmp/b.txt; exit 1; }
. scripts/gpu/env.sh x
root=$OUT
timeout 200 build/gpu/tests/ranryu_gl_tests > "$root/gl-tests.txt" 2>&1
echo "== GL suite rc $?: $(tail -2 "$root/gl-tests.txt" | head -1)"
grep -B3 -A12 "FAILED" "$root/gl-tests.txt" | head -60
export RANRYU_DFSPH_CAP=1.1,1
mkdir -p "$root/whole"
timeout 60 "$B" profile --scene dam-break --spacing 0.00317 --size 1920x1080 --frames 600 --warmup 0 \
  --records "$root/whole/db-246k.csv" > "$root/whole/db-246k.txt" 2>&1
echo "== whole pipeline 246k rc $?: $(grep -m1 'fps and real-time' "$root/whole/db-246k.txt")"
grep -h "^guard:\|^ranryu: simulation\|substeps/frame (\|density solve\|divergence solve" "$root/whole/db-246k.txt" | head -5
OUT=$root/db-1m SOLVER=dfsph PARTICLES=1000000 SCENES=dam-break RUN_TIMEOUT=130 timeout 140 scripts/gpu/scenes-seconds.sh 10 2>&1 | tail -4
grep -h "density solve\|divergence solve\|fps and real" "$root/db-1m/dam-break.txt"
OUT=$root/scenes-250k SOLVER=dfsph PARTICLES=250000 SCENES="drop turbulent-jet" RUN_TIMEOUT=40 timeout 90 scripts/gpu/scenes-seconds.sh 10 2>&1 | tail -6
OUT=$root/scenes-1m SOLVER=dfsph PARTICLES=1000000 SCENES="drop turbulent-jet" RUN_TIMEOUT=100 timeout 205 scripts/gpu/scenes-seconds.sh 10 2>&1 | tail -6
(cd "$root" && tar czf runs.tgz whole db-1m scenes-250k scenes-1m gl-tests.txt && rm -rf whole db-1m scenes-250k scenes-1m)
