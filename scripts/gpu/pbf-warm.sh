#!/usr/bin/env bash
# On the GPU host, after setup-and-build.sh (builds nothing): PBF's dam break (docs/PBF.md) at
# substeps x iterations with and without the warm start (P10). Usage:
#     scripts/gpu/pbf-warm.sh "VARIANTS" "SPACINGS" [frames] [warmup]
# VARIANTS: SxI or SxIwW (S substeps a frame, I iterations a substep, W the warm start's weight), e.g.
# "4x4 4x4w1 8x4w1"; SPACINGS in m (0.00317: 246k particles, 0.002: 1M). Each run is
# `ranryu profile --scene dam-break(variant) --solver pbf --spacing DX --size 1920x1080` from t = 0
# (--warmup frames first), the water shading; the impact on the far wall is at t = 0.4 s (frame 24).
# Prints per run the guard's verdict or the frame rate and real-time factor, the largest density and
# speed (from --records), and the solver's GPU ms a frame; reports under $OUT.
set -uo pipefail
cd "$(dirname "$0")/../.."
out=${OUT:-bench-out}
mkdir -p "$out"
B=${RANRYU_BIN:-build/gpu/app/ranryu}
variants=${1:-"4x4 4x4w1"}
spacings=${2:-"0.00317"}
frames=${3:-60}
warmup=${4:-0}
for v in $variants; do
  scene="$out/dam-break-pbf-$v.json"
  python3 - "$v" "$scene" <<'PY'
import json, re, sys
m = re.fullmatch(r"(\d+)x(\d+)(?:w([0-9.]+))?", sys.argv[1])
s = json.load(open("media/scenes/dam-break.json"))
s.pop("$schema", None)
s["name"] = f"dam-break-pbf-{sys.argv[1]}"
pbf = {"substeps": int(m[1]), "iterations": int(m[2])}
if m[3]: pbf["warm_start"] = float(m[3])
s.setdefault("sph", {})["pbf"] = pbf
json.dump(s, open(sys.argv[2], "w"), indent=1)
PY
  for dx in $spacings; do
    name="pbf-$v-$dx"
    timeout "${RUN_TIMEOUT:-300}" $B profile --scene "$scene" --solver pbf --spacing "$dx" --size 1920x1080 --frames "$frames" \
      --warmup "$warmup" --json "$out/$name.json" --records "$out/$name.csv" > "$out/$name.txt" 2>&1
    rc=$?
    verdict=$(grep -m1 -E "^ranryu: simulation" "$out/$name.txt" || grep -m1 -E "fps and real-time" "$out/$name.txt" || echo "rc $rc")
    peaks=$(python3 - "$out/$name.csv" <<'PY'
import csv, sys
try:
    rows = list(csv.DictReader(open(sys.argv[1])))
    print(f"max density {max(float(r['max_density']) for r in rows):.3f}, max speed {max(float(r['max_speed']) for r in rows):.2f} m/s over {len(rows)} frames")
except Exception as e:
    print(f"no records ({e})")
PY
)
    solver=$(awk '/^pbf\.|^(hash|sort\.|reorder|choose-time-step)/ {s += $2 * $6} END {printf "%.2f", s}' "$out/$name.txt")
    echo "== $v at $dx (rc $rc): $verdict; $peaks; solver+sort GPU ms a frame $solver"
  done
done
