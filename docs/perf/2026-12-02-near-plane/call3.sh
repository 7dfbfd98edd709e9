#!/usr/bin/env bash
# Call 3 (2026-12-02, night): how thin is the margin of the drop and the jet with `--solver dfsph` at
# about 1M particles ("The neighbour's kappa with its position", 2026-12-02: 1.544 and 1.800 rho0 for a
# frame, the guard's 1.5 passed as spikes)? Both scenes for ten seconds at three counts around 1M
# (other spacings, so other trajectories), as shipped, particle shading at 640x360; the records kept.
set -u
scripts/gpu/setup-and-build.sh ranryu > /tmp/b.txt 2>&1 || { tail -30 /tmp/b.txt; exit 1; }
. scripts/gpu/env.sh x
root=$OUT
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; date -u
for n in 930000 1000000 1070000; do
  OUT=$root/n$n SOLVER=dfsph PARTICLES=$n SCENES="drop turbulent-jet" RUN_TIMEOUT=95 scripts/gpu/scenes-seconds.sh 10 2>&1
  for s in drop turbulent-jet; do
    python3 - "$root/n$n/$s.csv" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
key = 'max_density'
v = [float(r[key]) for r in rows]
print(f"  {sys.argv[1].split('/')[-2]}/{sys.argv[1].split('/')[-1]}: {len(v)} frames, largest {max(v):.3f} ({key}), "
      f"frames past 1.1: {sum(x > 1.1 for x in v)}, 1.3: {sum(x > 1.3 for x in v)}, 1.5: {sum(x > 1.5 for x in v)}")
PY
  done
  rm -f "$root"/n$n/*.json
done
(cd "$root" && tar czf runs.tgz n* && rm -rf n*)
