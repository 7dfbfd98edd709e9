#!/usr/bin/env bash
# On the GPU host, after setup-and-build.sh: issue 14's budget, the surface and shading passes within
# 4 ms a frame at 1M particles and 1920x1080 (docs/PERFORMANCE.md, "The water shading's budget").
# Profiles the dam break at --spacing 0.002 (1,000,000 particles) in the water shading,
# `ranryu profile --frames 30 --warmup 10` (t = 0.17–0.67 s: the surge, the impact and the run-up; at 1M DFSPH stops on the guard at t = 1.14 s), with the water mode's options (docs/RENDERING.md (R13)):
#   budget       the defaults: the opaque scene cached per view, the thickness at half size, the
#                shadow map and the thickness rasterised in compute (R14)
#   draw-raster  RANRYU_WATER_RASTER=draw: those two passes drawn by the raster hardware (what the
#                compute raster saves)
#   full-thick   RANRYU_WATER_THICKNESS_DIVISOR=1: the thickness at the frame's size (what half size saves)
#   redraw       RANRYU_WATER_CACHE=0 as well: the opaque scene drawn every frame, as while the camera
#                moves (what the cache saves)
# and prints the surface's and the shading's passes, ms a frame, with their sums, beside the figures
# measured before these options (2026-11-25, same command). Writes to $OUT (or ./shading-budget-out):
#   summary.txt               that table
#   shading-budget.tar.gz     each run's profile JSON (--json), its table and log
# (only 8 files come back from the host: the reports travel in the tarball).
# `shading-budget.sh smoke` runs the same at the scene's own spacing, 320x180 and 3 frames (a check of
# the script on llvmpipe).
set -uo pipefail
cd "$(dirname "$0")/../.."
out=${OUT:-shading-budget-out}
mkdir -p "$out"
B=${RANRYU_BIN:-build/gpu/app/ranryu}
size=1920x1080 spacing=0.002 frames=30 warmup=10
if [ "${1:-}" = smoke ]; then size=320x180 spacing=0.0125 frames=3 warmup=1; fi
tmp=$(mktemp -d)

# profile NAME CACHE DIVISOR RASTER
profile() {
  local name=$1
  RANRYU_WATER_CACHE=$2 RANRYU_WATER_THICKNESS_DIVISOR=$3 RANRYU_WATER_RASTER=$4 \
    $B profile --scene dam-break --spacing $spacing --shading water --size $size --frames $frames --warmup $warmup \
    --json "$tmp/$name.json" > "$tmp/$name.txt" 2> "$tmp/$name.log"
  echo "== profile $name (RANRYU_WATER_CACHE=$2 RANRYU_WATER_THICKNESS_DIVISOR=$3 RANRYU_WATER_RASTER=$4): rc $?"
}
profile budget 1 2 compute
profile draw-raster 1 2 draw
profile full-thick 1 1 compute
profile redraw 0 1 compute

python3 - "$tmp" <<'PY' | tee "$out/summary.txt"
import json, sys
runs = ["budget", "draw-raster", "full-thick", "redraw"]
surface = ["surface.anisotropy", "surface.bounds", "level-set.splat", "level-set", "mc.classify", "mc.compact", "mc.emit"]
shading = ["shadow-map", "clear", "draw-sky", "draw-floor", "draw-walls", "draw-tank", "liquid-thickness", "compose",
           "draw-surface"]
# Measured before the scene cache, the compute clears and compose and the half-size thickness
# (docs/PERFORMANCE.md, "The water shading at 1M particles"; draw-tank was not listed there).
before = {"surface.anisotropy": 1.22, "surface.bounds": 0.04, "level-set.splat": 0.31, "level-set": 0.11,
          "mc.classify": 0.12, "mc.compact": 0.15, "mc.emit": 0.23, "shadow-map": 1.50, "clear": 0.44,
          "draw-sky": 0.30, "draw-floor": 0.54, "draw-walls": 0.26, "liquid-thickness": 1.14, "compose": 0.30,
          "draw-surface": 1.19}
reports = {}
for r in runs:
    try:
        reports[r] = json.load(open(f"{sys.argv[1]}/{r}.json"))
    except Exception as e:
        print(f"{r}: no report ({e})")
def ms(r, name):
    # Mean ms a frame over the timed frames: 0 for a pass that did not run in them (the cached
    # opaque scene is drawn in the first, warm-up, frame).
    for p in reports.get(r, {}).get("passes", []):
        if p["name"] == name:
            return float(p["ms_per_call"]) * float(p["calls_per_frame"])
    return 0.0
have = [r for r in runs if r in reports]
head = f"{'pass':22s} {'before':>8s}" + "".join(f" {r:>11s}" for r in have)
for r in have:
    rep = reports[r]
    print(f"{r}: {rep.get('device')} | {rep.get('driver')} | {rep.get('particles')} particles, "
          f"{rep.get('width')}x{rep.get('height')}, {rep.get('frames')} frames after {rep.get('warmup_frames')}; "
          f"frame (GPU span) {float(rep['frame']['ms_per_call']):.2f} ms")
print("\nms a frame (mean over the timed frames; 'before': 2026-11-25, docs/PERFORMANCE.md)")
for group, names in (("surface", surface), ("shading", shading)):
    print(head)
    for n in names:
        print(f"{n:22s} {before.get(n, 0.0):8.3f}" + "".join(f" {ms(r, n):11.3f}" for r in have))
    print(f"{'= ' + group:22s} {sum(before.get(n, 0.0) for n in names):8.3f}"
          + "".join(f" {sum(ms(r, n) for n in names):11.3f}" for r in have) + "\n")
print(f"{'= surface + shading':22s} {sum(before.values()):8.3f}"
      + "".join(f" {sum(ms(r, n) for n in surface + shading):11.3f}" for r in have) + "   (budget: 4 ms)")
PY
for r in budget draw-raster full-thick redraw; do grep -h "^surface (last frame)" "$tmp/$r.txt" | sed "s/^/$r: /"; done | tee -a "$out/summary.txt"
tar -czf "$out/shading-budget.tar.gz" -C "$tmp" . && echo "   $out/shading-budget.tar.gz"
rm -rf "$tmp"
