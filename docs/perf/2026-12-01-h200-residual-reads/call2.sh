#!/usr/bin/env bash
# Call 2 (2026-12-01): the residual pass's reads first (readsresidual) as committed: the dam break as
# shipped for ten seconds at 246k with the whole pipeline at 1920x1080 and at 1M with particles at
# 640x360; then the scenes that ship PBF (drop, jet, tank at rest) for ten seconds at about 250k and 1M
# with PBF's correction as one sum (owed since 147cc5e).
set -u
scripts/gpu/setup-and-build.sh ranryu > /tmp/b.txt 2>&1 || { tail -30 /tmp/b.txt; exit 1; }
. scripts/gpu/env.sh x
o=$OUT/c2; mkdir -p $o
{ nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; date -u; } | tee $o/device.txt
f=$o/db10-246k
timeout 60 $B profile --scene dam-break --spacing 0.00317 --size 1920x1080 --frames 600 --warmup 0 --records $f.csv > $f.txt 2>&1
echo "== 10 s 246k whole rc $?"; grep -E "^dfsph|^frame|substeps/frame|density solve:|fps and|guard" $f.txt
f=$o/db10-1m
timeout 150 $B profile --scene dam-break --spacing 0.002 --shading particles --size 640x360 --frames 600 --warmup 0 --records $f.csv > $f.txt 2>&1
echo "== 10 s 1M rc $?"; grep -E "^dfsph|^frame|substeps/frame|density solve:|fps and|guard" $f.txt
for n in 250000 1000000; do
  OUT=$o/pbf-$n SOLVER=pbf PARTICLES=$n SCENES="drop turbulent-jet hydrostatic" RUN_TIMEOUT=140 scripts/gpu/scenes-seconds.sh 10
done
(cd $OUT && tar czf c2.tgz c2 && rm -rf c2)
