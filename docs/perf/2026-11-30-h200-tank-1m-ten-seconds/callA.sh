#!/usr/bin/env bash
# The tank at rest with --solver dfsph (the pressure stabilisation (D12) as shipped) ten simulated seconds at
# about 1M particles, in two calls of one warm machine: a run takes longer than a call may. Call A builds,
# runs up to SECONDS_A of wall time and stops with SIGTERM, writing its checkpoint (--checkpoint) to the
# ignored build/gpu/, which a warm machine keeps for the next call; callB.sh goes on from it (--resume).
set -u
scripts/gpu/setup-and-build.sh ranryu > $OUT/build.txt 2>&1 || { tail -30 $OUT/build.txt; exit 1; }
. scripts/gpu/env.sh x
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | tee $OUT/device.txt; date -u | tee -a $OUT/device.txt
dx=$(python3 scripts/gpu/scene-at.py hydrostatic $OUT/hydrostatic.json 1000000)
rm -f build/gpu/tank1m.ckpt
timeout -s TERM ${SECONDS_A:-300} $B profile --scene $OUT/hydrostatic.json --solver dfsph --spacing $dx --shading particles --size 640x360 \
  --frames 600 --warmup 0 --records $OUT/a.csv --checkpoint build/gpu/tank1m.ckpt > $OUT/a.txt 2>&1
echo "rc $? spacing $dx; $(ls -l build/gpu/tank1m.ckpt)"
grep -E "particles|substeps/frame|density solve|^guard|^ranryu:" $OUT/a.txt | cut -c1-300
python3 docs/perf/2026-11-30-h200-tank-1m-ten-seconds/records.py "$OUT/a.csv"
