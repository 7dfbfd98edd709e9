#!/usr/bin/env bash
# On the GPU host, after setup-and-build.sh: the dam break as shipped (DFSPH with (D10)) for 10
# simulated seconds at about each N of NS particles (default 250000), once for each mean density error
# eta of ETAS (sph.max_density_error; default "1e-4 1e-3"), particle shading at 640x360; then the surge
# front at a/dx = 40 for each eta of FRONT_ETAS (default none). KEYS adds scene keys to every run
# ("sph.boundary_rows=true", dotted, as scene-at.py takes them); SHADERS runs a shader folder (--shader-dir). Prints each run's verdict, substeps,
# iterations, real-time factor and, from its per-frame records, the largest density and speed; the
# scenes, reports and records go under $OUT/eta (as $OUT/eta-$TAG.tgz when $OUT is set).
#     TAG=a NS="250000 1000000" ETAS="1e-4 5e-4" FRONT_ETAS="1e-4 5e-4" scripts/gpu/dfsph-eta.sh
. "$(dirname "$0")/env.sh" eta-out
out=${OUT:-eta-out}/eta
mkdir -p "$out"
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader
date -u
summary() {
  python3 - "$1" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
if not rows:
    sys.exit("   no records")
n = len(rows)
steps = sum(float(r["substeps"]) for r in rows)
iterations = sum(float(r["iterations"]) for r in rows)
print(f"   frames {n}, t {float(rows[-1]['time']):.2f}, substeps/frame {steps / n:.1f}, density iterations/step "
      f"{iterations / max(steps, 1):.2f}, divergence iterations/step "
      f"{sum(float(r['divergence_iterations']) for r in rows) / max(steps, 1):.2f}, largest rho/rho0 {max(float(r['max_density']) for r in rows):.3f}, "
      f"fastest {max(float(r['max_speed']) for r in rows):.1f} m/s, over the last 2 s {max(float(r['max_speed']) for r in rows[-120:]):.2f}, "
      f"steps at the cap {sum(int(r['unconverged']) for r in rows)}, "
      f"one particle's error at most {100 * max(float(r.get('peak_error') or 0) for r in rows):.3f} %")
PY
}
for n in ${NS:-250000}; do
  for eta in ${ETAS:-1e-4 1e-3}; do
    f=$out/db-$n-$eta
    dx=$(python3 scripts/gpu/scene-at.py dam-break "$f.json" "$n" sph.max_density_error="$eta" ${KEYS:-})
    start=$(date +%s)
    timeout "${RUN_TIMEOUT:-250}" $B profile --scene "$f.json" --spacing "$dx" --shading particles --size 640x360 \
      --frames "${FRAMES:-600}" --warmup 0 --records "$f.csv" ${SHADERS:+--shader-dir "$SHADERS"} > "$f.txt" 2>&1
    echo "== $n particles, eta $eta, spacing $dx: rc $?, $(( $(date +%s) - start )) s"
    grep -hE "substeps/frame \(|density solve|divergence solve|fps and real-time|^guard|^ranryu:" "$f.txt" | sed 's/^/   /'
    summary "$f.csv"
  done
done
for eta in ${FRONT_ETAS:-}; do
  f=$out/front-$eta
  python3 scripts/gpu/scene-at.py dam-break "$f.json" 1000 sph.max_density_error="$eta" ${KEYS:-} > /dev/null
  timeout 200 $B validate dam-break --scene "$f.json" --solver dfsph --spacing 0.005 --json "$f.out.json" --quiet > "$f.txt" 2>&1
  echo "== front at a/dx = 40, eta $eta: rc $? $(grep -m1 'surge front error' "$f.txt")"
done
if [ -n "${OUT:-}" ]; then tar czf "$OUT/eta-${TAG:-a}.tgz" -C "$OUT" eta && rm -rf "$OUT/eta"; fi
