#!/usr/bin/env bash
# On the GPU host, after setup-and-build.sh has built build/gpu (this script builds nothing): PBF
# (docs/PBF.md) at the lead's target sizes. Usage:
#     scripts/gpu/pbf.sh [frames] [warmup]
# 1. The dam break's whole pipeline (Fresnel surface at 1920x1080) with --solver pbf at the spacings
#    that give about 250k and 1M particles (fluid volume 0.008 m^3: 0.00317 and 0.002 m), at the
#    scene's defaults (4 substeps of 4 iterations, expected to fail there: docs/PBF.md "Resolution")
#    and at the variants PBF_VARIANTS (SUBSTEPSxITERATIONS,
#    each a copy of media/scenes/dam-break.json with "sph.pbf" set): GPU ms a frame, fps, every pass's
#    GPU ms a frame (pbf.lambda, pbf.correct, ... as `ranryu profile` names them), and whether the
#    guard fired (the impact on the far wall comes at t = 0.4 s: frame 24, within the default frames).
# 2. Every bundled SPH scene for 10 simulated seconds at about 250k particles with pbf at
#    PBF_SCENE_VARIANT (10x8, what the rule asks at 250k; each a copy of the bundled scene with
#    "sph.pbf" set and the spacing that fills its blocks with 250k particles), the guard watching:
#    no guard may fire. RUN_TIMEOUT bounds each run (560 s).
# Reports go to $OUT (or ./bench-out); $OUT/pbf-summary.txt holds the tables. For a look on a small
# machine first: PBF_SPACINGS=0.04 PBF_VARIANTS=2x2 PBF_SCENE_VARIANT=2x2 PBF_SCENE_PARTICLES=2000 PBF_SECONDS=0.1
# RANRYU_BIN=build/test/app/ranryu scripts/gpu/pbf.sh 3 1
set -uo pipefail
cd "$(dirname "$0")/../.."
out=${OUT:-bench-out}
mkdir -p "$out"
B=${RANRYU_BIN:-build/gpu/app/ranryu}
frames=${1:-60}
warmup=${2:-30}
# docs/PBF.md "Resolution": substeps x iterations >= 10 sqrt(2 g H) frame_dt / h, i.e. about 74 at
# 250k and 117 at 1M; the defaults' 16 suit the scene's own spacing only.
variants=${PBF_VARIANTS:-"10x8 12x10 30x4"}
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
scene_variant=${PBF_SCENE_VARIANT:-10x8}
: > "$out/pbf-scenes.txt"
for name in dam-break drop turbulent-jet hydrostatic; do
  file="$out/$name-pbf-$scene_variant.json"
  # The spacing that gives about 250k particles in the scene's blocks: (their volume / N)^(1/3).
  dx=$(python3 scripts/gpu/scene-at.py "$name" "$file" "${PBF_SCENE_PARTICLES:-250000}" name="$name-pbf-$scene_variant" \
    sph.pbf.substeps="${scene_variant%x*}" sph.pbf.iterations="${scene_variant#*x}")
  frames=$(python3 -c "print(max(1, round(${PBF_SECONDS:-10} * 60)))")
  run="pbf-scene-$name-$scene_variant"
  timeout "${RUN_TIMEOUT:-560}" $B profile --scene "$file" --solver pbf --spacing "$dx" --shading particles --size 640x360 \
    --frames "$frames" --warmup 0 --json "$out/$run.json" > "$out/$run.txt" 2>&1
  rc=$?
  outcome=$(grep -m1 "^ranryu:" "$out/$run.txt" || true)
  [ -z "$outcome" ] && { [ $rc = 0 ] && outcome=stable || outcome="rc $rc (timeout?)"; }
  particles=$(grep -m1 -oE "[0-9]+ particles" "$out/$run.txt" || true)
  echo "$name at $dx ($particles), $frames frames, $scene_variant: $outcome" | tee -a "$out/pbf-scenes.txt"
done
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
