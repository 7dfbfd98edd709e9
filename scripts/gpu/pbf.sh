#!/usr/bin/env bash
# On the GPU host, after setup-and-build.sh has built build/gpu (this script builds nothing): PBF
# (docs/PBF.md) at the lead's target sizes. Usage:
#     scripts/gpu/pbf.sh [frames] [warmup]
# 1. The dam break's whole pipeline (Fresnel surface at 1920x1080) with --solver pbf at the spacings
#    that give about 250k and 1M particles (fluid volume 0.008 m^3: 0.00317 and 0.002 m), at the
#    scene's defaults (4 substeps of 4 iterations) and at the variants PBF_VARIANTS (SUBSTEPSxITERATIONS,
#    each a copy of media/scenes/dam-break.json with "sph.pbf" set): GPU ms a frame, fps, every pass's
#    GPU ms a frame (pbf.lambda, pbf.correct, ... as `ranryu profile` names them), and whether the
#    guard fired (the impact on the far wall comes at t = 0.4 s: frame 24, within the default frames).
# 2. Every bundled scene for 10 simulated seconds at about 250k particles with pbf at its defaults, the
#    guard watching (scripts/gpu/check-scenes.sh "pbf" 250k 10): no guard may fire.
# Reports go to $OUT (or ./bench-out); $OUT/pbf-summary.txt holds the tables. For a look on a small
# machine first: PBF_SPACINGS="0.02" PBF_VARIANTS="2x2" PBF_SCALE=own PBF_SECONDS=0.5 RANRYU_BIN=build/test/app/ranryu.
set -uo pipefail
cd "$(dirname "$0")/../.."
out=${OUT:-bench-out}
mkdir -p "$out"
B=${RANRYU_BIN:-build/gpu/app/ranryu}
frames=${1:-60}
warmup=${2:-30}
variants=${PBF_VARIANTS:-"8x3 16x2"}
for v in default $variants; do
  scene=dam-break
  if [ "$v" != default ]; then
    scene="$out/dam-break-pbf-$v.json"
    python3 - "$v" "$scene" <<'PY'
import json, sys
substeps, iterations = (int(n) for n in sys.argv[1].split("x"))
s = json.load(open("media/scenes/dam-break.json"))
s.pop("$schema", None)
s["name"] = f"dam-break-pbf-{sys.argv[1]}"
s.setdefault("sph", {})["pbf"] = {"substeps": substeps, "iterations": iterations}
json.dump(s, open(sys.argv[2], "w"), indent=1)
PY
  fi
  for dx in ${PBF_SPACINGS:-0.00317 0.002}; do
    name="pbf-db-$v-$dx"
    timeout 560 $B profile --scene "$scene" --solver pbf --spacing "$dx" --size 1920x1080 --frames "$frames" --warmup "$warmup" \
      --json "$out/$name.json" > "$out/$name.txt" 2>&1
    echo "== $name (rc $?)"
    grep -E "^(ranryu:|simulation|  position|[0-9.]+ fps)" "$out/$name.txt"
  done
done
OUT="$out" RUN_TIMEOUT=${RUN_TIMEOUT:-560} scripts/gpu/check-scenes.sh "pbf" "${PBF_SCALE:-250k}" "${PBF_SECONDS:-10}" > "$out/pbf-scenes.txt" 2>&1
python3 - "$out" > "$out/pbf-summary.txt" <<'PY'
import json, sys, glob, os
out = sys.argv[1]
print("dam break, --solver pbf, 1920x1080 Fresnel surface (variant: substeps x iterations)")
print(f"{'variant':8} {'particles':>9} {'substeps':>8} {'GPU ms':>8} {'fps':>6} {'RTF gpu':>8}  passes (GPU ms a frame) / outcome")
for txt in sorted(glob.glob(os.path.join(out, "pbf-db-*.txt"))):
    variant = os.path.basename(txt)[len("pbf-db-"):].rsplit("-", 1)[0]
    bad = [l for l in open(txt).read().splitlines() if l.startswith("ranryu:")]
    js = txt[:-4] + ".json"
    if bad or not os.path.exists(js):
        print(f"{variant:8} {'':>9} {'':>8} {'':>8} {'':>6} {'':>8}  {bad[0] if bad else 'no result (timeout?)'}")
        continue
    j = json.load(open(js)); s = j.get("simulation", {})
    per_frame = lambda p: p["ms_per_call"] * p["calls_per_frame"]
    top = sorted(j.get("passes", []), key=lambda p: -per_frame(p))[:8]
    parts = ", ".join(f"{p['name']} {per_frame(p):.2f}" for p in top)
    print(f"{variant:8} {j['particles']:9d} {s.get('substeps_per_frame', 0):8.1f} {j['frame']['ms_per_call']:8.2f} {j['fps_gpu']:6.1f} "
          f"{j['real_time_factor_gpu']:8.3f}  {parts}")
print()
print(open(os.path.join(out, "pbf-scenes.txt")).read())
PY
cat "$out/pbf-summary.txt"
