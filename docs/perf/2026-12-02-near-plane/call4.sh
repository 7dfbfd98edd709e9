#!/usr/bin/env bash
# Call 4 (2026-12-02, night): do the drop's and the jet's floor-layer spikes with `--solver dfsph` at
# about 1M (call 3: 1.544 and 1.800 rho0 at the spacings scene-at.py picks for 1M) follow (D10)'s
# Chebyshev radius? The same two runs with sph.chebyshev 0.95 and 0.9 (shipped: 0.98).
set -u
scripts/gpu/setup-and-build.sh ranryu > /tmp/b.txt 2>&1 || { tail -30 /tmp/b.txt; exit 1; }
. scripts/gpu/env.sh x
root=$OUT
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; date -u
for rc in 0.95 0.9; do
  OUT=$root/rc$rc SOLVER=dfsph PARTICLES=1000000 SCENES="drop turbulent-jet" KEYS="sph.chebyshev=$rc" RUN_TIMEOUT=110 \
    scripts/gpu/scenes-seconds.sh 10 2>&1
  for s in drop turbulent-jet; do
    python3 - "$root/rc$rc/$s.csv" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
v = [float(r['max_density']) for r in rows]
it = sum(float(r['iterations']) for r in rows) / max(1.0, sum(float(r['substeps']) for r in rows))
print(f"  {'/'.join(sys.argv[1].split('/')[-2:])}: {len(v)} frames, largest {max(v):.3f}, frames past 1.1: "
      f"{sum(x > 1.1 for x in v)}, 1.3: {sum(x > 1.3 for x in v)}, 1.5: {sum(x > 1.5 for x in v)}; "
      f"{sum(float(r['substeps']) for r in rows) / len(rows):.1f} steps a frame, {it:.2f} density iterations a step")
PY
  done
  rm -f "$root"/rc$rc/*.json
done
(cd "$root" && tar czf runs.tgz rc* && rm -rf rc*)
