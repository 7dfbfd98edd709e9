#!/usr/bin/env bash
# On the GPU host, after setup-and-build.sh: the SPH benchmark of docs/PERFORMANCE.md. Writes every
# report under $OUT (or ./bench-out) and prints a summary. Scene variants (Morton keys, bitonic sort)
# are written as JSON next to the bundled dam break.
set -uo pipefail
cd "$(dirname "$0")/../.."
out=${OUT:-bench-out}
mkdir -p "$out"
B=build/gpu/app/ranryu
T=build/gpu/tests/ranryu_gl_tests
python3 - "$out" <<'PY'
import json, sys
s = json.load(open("media/scenes/dam-break.json"))
for name, sph in {"morton": {"neighbour_keys": "morton"}, "bitonic": {"sort": "bitonic"}}.items():
    v = dict(s); v["sph"] = dict(s["sph"], **sph); v["name"] = "dam-break-" + name
    json.dump(v, open(f"{sys.argv[1]}/dam-break-{name}.json", "w"))
PY
prof() {  # name, then ranryu profile arguments
  local name=$1; shift
  $B profile --size 640x360 --frames 6 --warmup 2 --json "$out/$name.json" "$@" > "$out/$name.txt" 2>&1
  echo "== $name (rc $?)"; grep -E "particles|^(hash|sort|cell|reorder|density|forces|integrate|choose)" "$out/$name.txt"
}
prof db-100k --scene dam-break --spacing 0.00431
prof db-1m --scene dam-break --spacing 0.002
prof db-1m-morton --scene "$out/dam-break-morton.json" --spacing 0.002
prof db-1m-bitonic --scene "$out/dam-break-bitonic.json" --spacing 0.002
prof db-4m --scene dam-break --spacing 0.00126
# Validation at GPU resolutions, and a picture of the 1M-particle dam break at T = 3.3 (t = 0.33 s).
$B validate dam-break --spacing 0.005 --json "$out/validate-dam-break-a40.json" > "$out/validate-dam-break-a40.txt" 2>&1
echo "== validate dam-break a/dx=40 (rc $?)"; tail -1 "$out/validate-dam-break-a40.txt"
$B validate dam-break --spacing 0.0025 --json "$out/validate-dam-break-a80.json" > "$out/validate-dam-break-a80.txt" 2>&1
echo "== validate dam-break a/dx=80 (rc $?)"; tail -1 "$out/validate-dam-break-a80.txt"
$B validate hydrostatic --json "$out/validate-hydrostatic.json" > "$out/validate-hydrostatic.txt" 2>&1
echo "== validate hydrostatic (rc $?)"; tail -1 "$out/validate-hydrostatic.txt"
rm -rf /tmp/ranryu-pic
$B record --scene dam-break --spacing 0.002 --frames 21 --size 1280x720 --out /tmp/ranryu-pic > "$out/record-1m.txt" 2>&1
echo "== record 1M (rc $?)"; grep -E "wrote|frame \(GPU" "$out/record-1m.txt"
cp /tmp/ranryu-pic/frame_00020.png "$out/dam-break-1m-frame20.png" 2>/dev/null
cp /tmp/ranryu-pic/run.json "$out/record-1m-run.json" 2>/dev/null
