#!/usr/bin/env bash
# Call 5 (2026-12-02, night): sph.chebyshev 0.95 for the drop and the jet with `--solver dfsph` at the
# other two counts of call 3 (about 930k and 1.07M) and at about 250k, ten seconds each, particle
# shading at 640x360 (call 4 ran it at about 1M).
set -u
scripts/gpu/setup-and-build.sh ranryu > /tmp/b.txt 2>&1 || { tail -30 /tmp/b.txt; exit 1; }
. scripts/gpu/env.sh x
root=$OUT
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; date -u
for n in 250000 930000 1070000; do
  OUT=$root/n$n SOLVER=dfsph PARTICLES=$n SCENES="drop turbulent-jet" KEYS="sph.chebyshev=0.95" RUN_TIMEOUT=75 \
    scripts/gpu/scenes-seconds.sh 10 2>&1
  for s in drop turbulent-jet; do
    python3 - "$root/n$n/$s.csv" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
v = [float(r['max_density']) for r in rows]
it = sum(float(r['iterations']) for r in rows) / max(1.0, sum(float(r['substeps']) for r in rows))
print(f"  {'/'.join(sys.argv[1].split('/')[-2:])}: {len(v)} frames, largest {max(v):.3f}, frames past 1.1: "
      f"{sum(x > 1.1 for x in v)}, 1.3: {sum(x > 1.3 for x in v)}, 1.5: {sum(x > 1.5 for x in v)}; "
      f"{sum(float(r['substeps']) for r in rows) / len(rows):.1f} steps a frame, {it:.2f} density iterations a step")
PY
  done
  rm -f "$root"/n$n/*.json
done
(cd "$root" && tar czf runs.tgz n* && rm -rf n*)
