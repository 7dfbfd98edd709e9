#!/usr/bin/env bash
# Call B (see callA.sh): goes on from call A's checkpoint to frame 600 (ten simulated seconds), within
# SECONDS_B of wall time (SIGTERM after: it then writes how far it got).
set -u
. scripts/gpu/env.sh x
[ -f build/gpu/tank1m.ckpt ] || { echo "no checkpoint: the machine was not the warm one of call A"; exit 1; }
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | tee $OUT/device.txt; date -u | tee -a $OUT/device.txt
done_frames=$(python3 -c "
import json, struct
f = open('build/gpu/tank1m.ckpt', 'rb'); f.read(8); f.read(4); n = struct.unpack('<Q', f.read(8))[0]
print(json.loads(f.read(n))['frame'])")
echo "checkpoint at frame $done_frames"
timeout -s TERM ${SECONDS_B:-360} $B profile --resume build/gpu/tank1m.ckpt --shading particles --size 640x360 \
  --frames $((600 - done_frames)) --warmup 0 --records $OUT/b.csv --checkpoint build/gpu/tank1m-b.ckpt > $OUT/b.txt 2>&1
echo "rc $?"
grep -E "particles|substeps/frame|density solve|^guard|^ranryu:" $OUT/b.txt | cut -c1-300
python3 docs/perf/2026-11-30-h200-tank-1m-ten-seconds/records.py "$OUT/b.csv"
