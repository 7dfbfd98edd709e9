#!/usr/bin/env bash
# Session 22, call 4: the drop and the jet with --solver dfsph at sph.dfsph_cfl 0.5 (246k, 1M); the dam
# break as shipped with eta_p = 2e-2 (246k, 1M).
cd "$(dirname "$0")/.."
scripts/gpu/setup-and-build.sh ranryu > $OUT/build.txt 2>&1 || { tail -30 $OUT/build.txt; exit 1; }
tail -1 $OUT/build.txt
R=$OUT/r; mkdir -p $R
for n in 250000 1000000; do
  SOLVER=dfsph PARTICLES=$n SCENES="drop turbulent-jet" KEYS="sph.dfsph_cfl=0.5" RUN_TIMEOUT=200 OUT=$R/dj-$n \
    scripts/gpu/scenes-seconds.sh 10 2>&1 | grep -v "why its" > $R/dj-$n.txt; cat $R/dj-$n.txt
  for s in drop turbulent-jet; do python3 - $R/dj-$n/$s.csv <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
n = len(rows); st = sum(float(r["substeps"]) for r in rows); it = sum(float(r["iterations"]) for r in rows)
print(f"   {sys.argv[1]}: frames {n}, steps/frame {st/n:.1f}, it/step {it/st:.2f}, largest {max(float(r['max_density']) for r in rows):.3f}, "
      f"fastest {max(float(r['max_speed']) for r in rows):.1f}, last 2 s {max(float(r['max_speed']) for r in rows[-120:]):.2f}, at the cap {sum(int(r['unconverged']) for r in rows)}")
PY
  done
done
TAG=peak2 KEYS="sph.max_particle_density_error=2e-2" ETAS=1e-3 NS="250000 1000000" OUT=$R scripts/gpu/dfsph-eta.sh 2>&1 | grep -v "why its" > $R/peak2.txt; cat $R/peak2.txt
find $R -name "*.txt" -exec sed -i '/why its settings/d' {} \;
tar czf $OUT/call4.tgz -C $OUT r && rm -rf $R
