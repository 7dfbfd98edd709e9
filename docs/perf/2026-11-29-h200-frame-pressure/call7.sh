#!/usr/bin/env bash
# The rows' Chebyshev step (call 5's tree): the tank at rest with --solver dfsph at about 1M particles
# for ten simulated seconds, the guard watching (1.9 fps on 2026-11-28: about 320 s).
scripts/gpu/setup-and-build.sh ranryu >/dev/null 2>&1 || { echo build failed; exit 1; }
. scripts/gpu/env.sh x
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $out/device.txt; date -u >> $out/device.txt
OUT=$out/s1000000 SOLVER=dfsph PARTICLES=1000000 SCENES=hydrostatic RUN_TIMEOUT=390 scripts/gpu/scenes-seconds.sh 10
python3 - $out/s1000000/hydrostatic.csv <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
n = len(rows); steps = sum(float(r["substeps"]) for r in rows)
print(f"   frames {n}, t {float(rows[-1]['time']):.2f}, substeps/frame {steps / n:.1f}, density iterations/step {sum(float(r['iterations']) for r in rows) / max(steps, 1):.2f}, "
      f"at the cap {sum(int(r['unconverged']) for r in rows)}, largest rho/rho0 {max(float(r['max_density']) for r in rows):.3f}, "
      f"fastest {max(float(r['max_speed']) for r in rows):.1f} m/s, over the last 2 s {max(float(r['max_speed']) for r in rows[-120:]):.2f}")
PY
grep -h "fps and real-time\|^guard\|^ranryu:" $out/s1000000/hydrostatic.txt
rm -f $out/s1000000/*.csv
