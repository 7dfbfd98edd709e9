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
python3 - "$OUT/b.csv" <<'PY'
import csv, sys
r = list(csv.DictReader(open(sys.argv[1])))
s = sum(float(x["substeps"]) for x in r)
print(f"{len(r)} frames ({r[0]['frame']}..{r[-1]['frame']}), t {float(r[-1]['time']):.3f} s, {s / len(r):.1f} steps/frame, "
      f"{sum(float(x['iterations']) for x in r) / s:.2f} density iterations/step, largest rho/rho0 {max(float(x['max_density']) for x in r):.4f}, "
      f"fastest {max(float(x['max_speed']) for x in r):.2f} m/s, nan {sum(int(x['nan']) for x in r)}, escaped {sum(int(x['escaped']) for x in r)}")
PY
