#!/usr/bin/env bash
# On the GPU host, after setup-and-build.sh: the 1M-particle dam break (spacing 0.002) with the guard's
# speed bound raised to SPEED m/s (default 50; the scene's derived bound is 15.7 m/s), to tell a fast
# but bounded splash from a blow-up (docs/DFSPH.md "The dam break at 1M particles stopped at t = 1.16 s:
# a one-frame spike"). SPEED 0 keeps the scene's own bound (the guard's two-frame rule then applies).
# Each solver's per-frame record (largest speed, largest density, substeps) goes to $OUT/SOLVER.csv.
# Usage:
#     scripts/gpu/db-1m-speed.sh ["pbf:600 dfsph:150"] [SPEED]     # solver:frames
. "$(dirname "$0")/env.sh" bench-out
runs=${1:-pbf:600 dfsph:150}
speed=${2:-50}
python3 - "$out/dam-break.json" "$speed" <<'PY'
import json, sys
s = json.load(open("media/scenes/dam-break.json"))
s.pop("$schema", None)
s.setdefault("sph", {})["speed_limit"] = float(sys.argv[2])
json.dump(s, open(sys.argv[1], "w"), indent=1)
PY
for r in $runs; do
  solver=${r%%:*} frames=${r#*:}
  timeout "${RUN_TIMEOUT:-200}" $B profile --scene "$out/dam-break.json" --solver "$solver" --spacing 0.002 \
    --shading particles --size 640x360 --frames "$frames" --warmup 0 --records "$out/$solver.csv" > "$out/$solver.txt" 2>&1
  rc=$?
  verdict=$(grep -m1 "^ranryu: simulation" "$out/$solver.txt" || grep -m1 "fps and real-time" "$out/$solver.txt" || echo "rc $rc")
  echo "$solver, $frames frames, speed bound $speed m/s: $verdict"
done
