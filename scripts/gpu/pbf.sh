#!/usr/bin/env bash
# On the GPU host, after setup-and-build.sh has built build/gpu (this script builds nothing): PBF
# (docs/PBF.md) at the lead's target sizes. Usage:
#     scripts/gpu/pbf.sh [frames] [warmup]
# 1. The dam break's whole pipeline (Fresnel surface at 1920x1080) with --solver pbf at the spacings
#    that give about 250k and 1M particles (fluid volume 0.008 m^3: 0.00317 and 0.002 m): GPU ms a
#    frame, fps and every pass's share (pbf.lambda, pbf.correct, ... as `ranryu profile` names them).
# 2. Every bundled scene for 10 simulated seconds at about 250k particles with pbf, the guard
#    watching (scripts/gpu/check-scenes.sh "pbf" 250k 10): no guard may fire.
# Reports go to $OUT (or ./bench-out); $OUT/pbf-summary.txt holds the tables.
set -uo pipefail
cd "$(dirname "$0")/../.."
out=${OUT:-bench-out}
mkdir -p "$out"
B=${RANRYU_BIN:-build/gpu/app/ranryu}
frames=${1:-60}
warmup=${2:-30}
for dx in 0.00317 0.002; do
  name="pbf-db-$dx"
  timeout 560 $B profile --scene dam-break --solver pbf --spacing "$dx" --size 1920x1080 --frames "$frames" --warmup "$warmup" \
    --json "$out/$name.json" > "$out/$name.txt" 2>&1
  echo "== $name (rc $?)"
  cat "$out/$name.txt"
done
OUT="$out" RUN_TIMEOUT=${RUN_TIMEOUT:-560} scripts/gpu/check-scenes.sh "pbf" 250k 10 > "$out/pbf-scenes.txt" 2>&1
python3 - "$out" > "$out/pbf-summary.txt" <<'PY'
import json, sys, glob, os
out = sys.argv[1]
print("dam break, --solver pbf, 1920x1080 Fresnel surface")
print(f"{'particles':>9} {'substeps':>8} {'GPU ms':>8} {'fps':>6} {'RTF gpu':>8}  passes (GPU ms a frame)")
for f in sorted(glob.glob(os.path.join(out, "pbf-db-*.json"))):
    j = json.load(open(f)); s = j.get("simulation", {})
    passes = {p["name"]: p for p in j.get("passes", [])}
    top = sorted(passes.values(), key=lambda p: -p.get("ms_per_frame", 0))[:8]
    parts = ", ".join(f"{p['name']} {p.get('ms_per_frame', 0):.2f}" for p in top)
    print(f"{j['particles']:9d} {s.get('substeps_per_frame', 0):8.1f} {j['frame']['ms_per_call']:8.2f} {j['fps_gpu']:6.1f} "
          f"{j['real_time_factor_gpu']:8.3f}  {parts}")
print()
print(open(os.path.join(out, "pbf-scenes.txt")).read())
PY
cat "$out/pbf-summary.txt"
