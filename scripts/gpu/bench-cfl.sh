#!/usr/bin/env bash
# On the GPU host, after setup-and-build.sh: DFSPH's time-step factor (the Courant number of docs/DFSPH.md
# (D8), sph.dfsph_cfl, which the dam break sets and WCSPH does not read) on the dam break: for each spacing and factor, the whole pipeline (Fresnel surface at
# 1920x1080; substeps and iterations a frame, unconverged steps, GPU ms, fps, real-time factor) and the
# surge front against Martin & Moyce at a/dx = 40. Usage:
#     scripts/gpu/bench-cfl.sh "0.00317 0.002" "0.4 0.6 0.8" [frames] [warmup]
# RANRYU_BIN picks the binary (build/gpu/app/ranryu), TAG prefixes the reports in $OUT (./bench-out).
set -uo pipefail
cd "$(dirname "$0")/../.."
out=${OUT:-bench-out}
mkdir -p "$out"
B=${RANRYU_BIN:-build/gpu/app/ranryu}
tag=${TAG:-cfl}
spacings=${1:-"0.00317 0.002"}
factors=${2:-"0.4 0.6 0.8"}
frames=${3:-20}
warmup=${4:-20}
scenes=$(mktemp -d)
for f in $factors; do
  python3 - "$f" "$scenes/dam-break-cfl$f.json" <<'PY'
import json, sys
s = json.load(open("media/scenes/dam-break.json"))
s.setdefault("sph", {})["dfsph_cfl"] = float(sys.argv[1])
json.dump(s, open(sys.argv[2], "w"))
PY
  for dx in $spacings; do
    name="$tag-db-$dx-cfl$f"
    timeout 300 $B profile --scene "$scenes/dam-break-cfl$f.json" --solver dfsph --spacing "$dx" --size 1920x1080 \
      --frames "$frames" --warmup "$warmup" --json "$out/$name.json" > "$out/$name.txt" 2>&1
    echo "== $name (rc $?)"; grep -E "^(ranryu:|simulation)" "$out/$name.txt"
  done
  timeout 120 $B validate dam-break --scene "$scenes/dam-break-cfl$f.json" --solver dfsph --spacing 0.005 \
    --json "$out/$tag-front-cfl$f.json" 2>&1 | grep -E "^(ranryu:|surge|dfsph)" | sed "s/^/cfl $f: /"
done
python3 - "$out" "$tag" <<'PY'
import json, sys, glob, os
print(f"{'report':32} {'particles':>9} {'substeps':>8} {'iter':>5} {'max':>4} {'unconv':>6} {'max err':>8} {'GPU ms':>8} {'fps':>6} {'RTF':>6}")
for f in sorted(glob.glob(os.path.join(sys.argv[1], sys.argv[2] + "-db-*.json"))):
    j = json.load(open(f)); s = j.get("simulation", {})
    print(f"{os.path.basename(f)[:-5]:32} {j['particles']:9d} {s.get('substeps_per_frame', 0):8.1f} {s.get('iterations_per_step', 0):5.2f} "
          f"{s.get('most_iterations', 0):4d} {s.get('unconverged_steps', 0):6d} {s.get('max_density_error', 0):8.2e} "
          f"{j['frame']['ms_per_call']:8.2f} {j['fps_gpu']:6.1f} {j['real_time_factor_gpu']:6.3f}")
PY
