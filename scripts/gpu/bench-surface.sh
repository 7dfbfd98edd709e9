#!/usr/bin/env bash
# On the GPU host, after setup-and-build.sh: the surface passes of docs/PERFORMANCE.md for the 1M
# particle dam break with Fresnel shading, at level-set grids capped at 128 and 160 nodes an axis,
# and a picture of frame 20. Reports go to $OUT (or ./bench-out).
set -uo pipefail
cd "$(dirname "$0")/../.."
out=${OUT:-bench-out}
mkdir -p "$out"
B=build/gpu/app/ranryu
for n in 128 160; do
  python3 - "$out" "$n" <<'PY'
import json, sys
s = json.load(open("media/scenes/dam-break.json"))
s["surface"] = {"node_spacing": 0.5, "max_dims": int(sys.argv[2])}
s["name"] = "dam-break-surface-" + sys.argv[2]
json.dump(s, open(f"{sys.argv[1]}/dam-break-surface-{sys.argv[2]}.json", "w"))
PY
  $B profile --scene "$out/dam-break-surface-$n.json" --spacing 0.002 --shading fresnel --size 1280x720 \
     --frames 6 --warmup 2 --json "$out/surface-$n.json" > "$out/surface-$n.txt" 2>&1
  echo "== max_dims $n (rc $?)"
  grep -E "^(surface|level-set|mc\.|draw-surface|density|forces)|triangles" "$out/surface-$n.txt"
done
rm -rf /tmp/ranryu-fresnel
$B record --scene dam-break --spacing 0.002 --shading fresnel --frames 21 --size 1280x720 --out /tmp/ranryu-fresnel > "$out/record-fresnel.txt" 2>&1
echo "== record fresnel (rc $?)"; grep -E "wrote" "$out/record-fresnel.txt"
cp /tmp/ranryu-fresnel/frame_00020.png "$out/dam-break-1m-fresnel-frame20.png" 2>/dev/null
