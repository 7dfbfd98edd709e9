#!/usr/bin/env bash
# On the GPU host, after setup-and-build.sh: the liquid surface's cost at 1M particles (docs/SURFACE.md
# (S9); the issue's budget: surface + shading <= 4 ms a frame). The dam break at --spacing 0.002
# (100 x 200 x 50 = 1,000,000 particles), Fresnel shading at 1920x1080, with anisotropic kernels on
# and off (the default node budget, 2^23 nodes), profiled over frames 20-27 (the surge, splashes).
# Writes to $OUT (or ./bench-out):
#   surface-aniso-{on,off}.json / .txt    per-pass timings (ranryu profile --json) and its table
#   dam-break-1m-aniso-{on,off}.png       frame 30 of a record at 1920x1080 (the surface's look)
#   summary.txt                           the surface and shading passes of both runs, ms a frame
set -uo pipefail
cd "$(dirname "$0")/../.."
out=${OUT:-bench-out}
mkdir -p "$out"
B=build/gpu/app/ranryu
for mode in on off; do
  python3 - /tmp "$mode" <<'PY'
import json, sys
s = json.load(open("media/scenes/dam-break.json"))
s["surface"] = {"anisotropic": sys.argv[2] == "on"}
s["name"] = "dam-break-aniso-" + sys.argv[2]
json.dump(s, open(f"{sys.argv[1]}/dam-break-aniso-{sys.argv[2]}.json", "w"))
PY
  scene="/tmp/dam-break-aniso-$mode.json"   # not under $OUT: 8 files come back
  $B profile --scene "$scene" --spacing 0.002 --shading fresnel --size 1920x1080 \
     --frames 8 --warmup 20 --json "$out/surface-aniso-$mode.json" > "$out/surface-aniso-$mode.txt" 2>&1
  echo "== anisotropic $mode (profile rc $?)"
  rm -rf "/tmp/ranryu-aniso-$mode"
  $B record --scene "$scene" --spacing 0.002 --shading fresnel --size 1920x1080 --frames 31 \
     --out "/tmp/ranryu-aniso-$mode" > "/tmp/ranryu-aniso-$mode.log" 2>&1
  echo "== record $mode (rc $?)"
  cp "/tmp/ranryu-aniso-$mode/frame_00030.png" "$out/dam-break-1m-aniso-$mode.png" 2>/dev/null
done
python3 - "$out" <<'PY' | tee "$out/summary.txt"
import json, sys
# The surface's passes (level set, marching cubes) and the shading's (the raster passes).
surface = ["surface.anisotropy", "surface.bounds", "level-set.splat", "level-set", "mc.classify", "mc.compact", "mc.emit"]
for mode in ["on", "off"]:
    try:
        report = json.load(open(f"{sys.argv[1]}/surface-aniso-{mode}.json"))
    except Exception as e:
        print(f"anisotropic {mode}: no report ({e})")
        continue
    passes = {p.get("name"): p for p in report.get("passes", [])}
    def ms(name):
        p = passes.get(name)
        if not p:
            return 0.0
        return float(p["ms_per_call"]) * float(p["calls_per_frame"])
    s = sum(ms(n) for n in surface)
    d = sum(ms(n) for n in passes if n.startswith("draw-") or n == "clear")
    print(f"anisotropic {mode}: surface {s:.3f} ms + shading {d:.3f} ms = {s + d:.3f} ms a frame (budget 4 ms); "
          f"{report.get('particles')} particles, mesh {report.get('surface')}")
    for n in surface + sorted(n for n in passes if n.startswith("draw-") or n == "clear"):
        if n in passes:
            print(f"    {n:22s} {ms(n):8.3f}")
PY
