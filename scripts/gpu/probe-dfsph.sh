#!/usr/bin/env bash
# On the GPU host, after setup-and-build.sh: the dam break with variants of its "sph" settings, each
# recorded frame by frame (--records), to see how a solver setting changes the run. Usage:
#     scripts/gpu/probe-dfsph.sh SPACING FRAMES 'name={"key": value, ...}' ...
# Each variant's records go to $OUT/NAME.csv, its output to $OUT/NAME.txt; the last lines are printed.
set -uo pipefail
cd "$(dirname "$0")/../.."
out=${OUT:-bench-out}
mkdir -p "$out"
dx=$1 frames=$2
shift 2
for v in "$@"; do
  name=${v%%=*} sph=${v#*=}
  python3 - "$out/$name.scene.json" "$sph" <<'PY'
import json, sys
s = json.load(open("media/scenes/dam-break.json"))
s["sph"].update(json.loads(sys.argv[2])); s["name"] = "dam-break"
json.dump(s, open(sys.argv[1], "w"))
PY
  timeout 300 build/gpu/app/ranryu profile --scene "$out/$name.scene.json" --spacing "$dx" --shading particles --size 640x360 \
    --frames "$frames" --warmup 0 --records "$out/$name.csv" > "$out/$name.txt" 2>&1
  echo "== $name (rc $?)"; grep -E "^(simulation|  density|  divergence|[0-9.]+ fps|ranryu:|dfsph|frame )" "$out/$name.txt"
done
