#!/usr/bin/env bash
# On the GPU host, after setup-and-build.sh, with Dear ImGui carried in .gl/ (here:
# ../shared/gpu-host/fetch-debs.sh nlohmann-json3-dev libimgui-dev, so that the headless build finds
# libimgui.a and its backends' sources; without it, --overlay is refused with exit 2): the window's
# overlay cost (issue 13), measured where no window can open. `ranryu profile --overlay` draws the
# panel into the offscreen target after every frame: the pass "overlay" is its GPU time, and the
# "overlay: CPU" line its CPU time (building the panel and recording its draws). The dam break, the
# window's default Fresnel surface, 1920x1080, with and without the overlay, at each spacing:
#     scripts/gpu/overlay.sh ["0.01 0.006 0.004"] [frames] [warmup]
# Reports go to $OUT (or ./overlay-out); the summary table, printed last, is also $OUT/summary.txt.
# "realtime" says whether the frame rate by the GPU's frame spans reaches 60 fps and the real-time
# factor 1 (the window's rate without vsync is at most that: it adds the present and the swap).
set -uo pipefail
cd "$(dirname "$0")/../.."
out=${OUT:-overlay-out}
mkdir -p "$out"
B=build/gpu/app/ranryu
spacings=${1:-"0.01 0.006 0.004"}
frames=${2:-120}
warmup=${3:-30}
for dx in $spacings; do
  for mode in plain overlay; do
    name="db-$dx-$mode"
    extra=""
    [ "$mode" = overlay ] && extra="--overlay"
    timeout 560 $B profile --scene dam-break --spacing "$dx" --size 1920x1080 --frames "$frames" --warmup "$warmup" $extra \
      --json "$out/$name.json" --quiet > "$out/$name.txt" 2>&1
    echo "== $name (rc $?)"
    grep -E "^(overlay|[0-9.]+ fps)" "$out/$name.txt"
  done
done
python3 - "$out" <<'PY' | tee "$out/summary.txt"
import json, sys, glob, os
out = sys.argv[1]
print(f"{'spacing':>8} {'particles':>9} {'mode':7} {'GPU ms':>8} {'overlay GPU ms':>14} {'overlay CPU ms':>14} {'fps gpu':>8} {'RTF gpu':>8} {'fps wall':>8} realtime")
for f in sorted(glob.glob(os.path.join(out, "db-*.json"))):
    j = json.load(open(f))
    dx, mode = os.path.basename(f)[3:-5].rsplit("-", 1)
    gpu = {p["name"]: p["ms_per_call"] for p in j["passes"]}
    ov = j.get("overlay", {})
    fps = j["fps_gpu"]; rtf = j["real_time_factor_gpu"]
    wall = j.get("fps_wall", float("nan"))
    print(f"{dx:>8} {j['particles']:9d} {mode:7} {j['frame']['ms_per_call']:8.3f} {gpu.get('overlay', float('nan')):14.4f} "
          f"{ov.get('cpu_ms_mean', float('nan')):14.4f} {fps:8.1f} {rtf:8.3f} {wall:8.1f} {'yes' if fps >= 60 and rtf >= 1 else 'no'}")
PY
