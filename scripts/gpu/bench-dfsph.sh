#!/usr/bin/env bash
# On the GPU host, after setup-and-build.sh: the dam break's whole pipeline (Fresnel surface at
# 1920x1080) with each solver at several resolutions: substeps a frame, solver iterations, GPU ms a
# frame, fps and the real-time factor (docs/PERFORMANCE.md). Usage:
#     scripts/gpu/bench-dfsph.sh "dfsph wcsph" "0.005 0.004 0.00317 0.0025 0.002" [frames] [warmup]
# Reports go to $OUT (or ./bench-out); a summary table is printed last.
set -uo pipefail
cd "$(dirname "$0")/../.."
out=${OUT:-bench-out}
mkdir -p "$out"
B=build/gpu/app/ranryu
solvers=${1:-"dfsph wcsph"}
spacings=${2:-"0.005 0.004 0.00317 0.0025 0.002"}
frames=${3:-30}
warmup=${4:-30}
for s in $solvers; do
  for dx in $spacings; do
    name="db-$s-$dx"
    timeout 560 $B profile --scene dam-break --solver "$s" --spacing "$dx" --size 1920x1080 --frames "$frames" --warmup "$warmup" \
      --json "$out/$name.json" > "$out/$name.txt" 2>&1
    echo "== $name (rc $?)"
    grep -E "^(simulation|  density|  divergence|[0-9.]+ fps)" "$out/$name.txt"
  done
done
python3 - "$out" <<'PY'
import json, sys, glob, os
rows = []
for f in sorted(glob.glob(os.path.join(sys.argv[1], "db-*.json"))):
    j = json.load(open(f)); s = j.get("simulation", {})
    rows.append((s.get("solver", "?"), j["particles"], s.get("substeps_per_frame", 0), s.get("iterations_per_step", 0),
                 s.get("divergence_iterations_per_step", 0), j["frame"]["ms_per_call"], j["fps_gpu"], j["real_time_factor_gpu"],
                 j["real_time_factor_wall"]))
print(f"{'solver':6} {'particles':>9} {'substeps':>8} {'iter':>5} {'div':>5} {'GPU ms':>8} {'fps':>6} {'RTF gpu':>8} {'RTF wall':>8}")
for r in rows:
    print(f"{r[0]:6} {r[1]:9d} {r[2]:8.1f} {r[3]:5.2f} {r[4]:5.2f} {r[5]:8.2f} {r[6]:6.1f} {r[7]:8.3f} {r[8]:8.3f}")
PY
