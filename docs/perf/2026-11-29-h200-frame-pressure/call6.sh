#!/usr/bin/env bash
# The rows' Chebyshev step (call 5's tree): the other bundled SPH scenes with --solver dfsph for ten
# simulated seconds, the guard watching: the drop, the jet and the tank at rest at about 250k, the drop
# and the jet at about 1M (the tank at 1M, 1.9 fps on 2026-11-28, does not fit the call).
scripts/gpu/setup-and-build.sh ranryu >/dev/null 2>&1 || { echo build failed; exit 1; }
. scripts/gpu/env.sh x
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $out/device.txt; date -u >> $out/device.txt
summary() {
  python3 - "$1" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
if not rows:
    sys.exit("   no records")
n = len(rows); steps = sum(float(r["substeps"]) for r in rows)
print(f"   frames {n}, substeps/frame {steps / n:.1f}, density iterations/step {sum(float(r['iterations']) for r in rows) / max(steps, 1):.2f}, "
      f"at the cap {sum(int(r['unconverged']) for r in rows)}, largest rho/rho0 {max(float(r['max_density']) for r in rows):.3f}, "
      f"fastest {max(float(r['max_speed']) for r in rows):.1f} m/s, over the last 2 s {max(float(r['max_speed']) for r in rows[-120:]):.2f}")
PY
}
for run in "250000 drop turbulent-jet hydrostatic" "1000000 drop turbulent-jet"; do
  set -- $run; n=$1; shift
  OUT=$out/s$n SOLVER=dfsph PARTICLES=$n SCENES="$*" RUN_TIMEOUT=150 scripts/gpu/scenes-seconds.sh 10
  for s in "$@"; do summary $out/s$n/$s.csv; grep -h "fps and real-time" $out/s$n/$s.txt | sed 's/^/   /'; done
done
rm -f $out/s*/*.csv
tar czf $out/scenes.tgz -C $out s250000 s1000000 && rm -rf $out/s250000 $out/s1000000
