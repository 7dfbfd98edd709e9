#!/usr/bin/env bash
# On the GPU host, after setup-and-build.sh all: the turbulence tests on the GPU, and the wavelet
# and turbulence-force passes in the turbulent jet at ~1M particles, with the force on and off.
set -uo pipefail
cd "$(dirname "$0")/../.."
out=${OUT:-bench-out}
mkdir -p "$out"
B=build/gpu/app/ranryu
build/gpu/tests/ranryu_gl_tests "[turbulence],[wavelet],[noise]" 2>&1 | grep -v "GL message" | tail -2
python3 - "$out" <<'PY'
import json, sys
s = json.load(open("media/scenes/turbulent-jet.json"))
s["turbulence"]["amplitude"] = 0.0; s["name"] = "turbulent-jet-off"
json.dump(s, open(f"{sys.argv[1]}/turbulent-jet-off.json", "w"))
PY
for v in media/scenes/turbulent-jet.json "$out/turbulent-jet-off.json"; do
  $B profile --scene "$v" --spacing 0.003 --shading particles --size 320x180 --frames 6 --warmup 2 \
     --json "$out/$(basename "$v" .json).json" > "$out/$(basename "$v" .json).txt" 2>&1
  echo "== $v (rc $?)"; grep -E "particles,|^(wavelet|turbulence|density|forces|integrate|sort\.scatter)" "$out/$(basename "$v" .json).txt"
done
$B export-field --size 256 --out /tmp/f.npy --force 2>&1 | tail -2
