#!/bin/bash
# The runs of this folder (llvmpipe, a debug build: build/test/app/ranryu), from the project root:
#   docs/perf/2026-11-29-llvmpipe-tank-at-rest-motion/run.sh SPACING AVERAGE_S VARIANT...
# e.g. `run.sh 0.0125 1 base div5` (1 s settled, then AVERAGE_S averaged). Outputs to $OUT (default /tmp/tank).
set -euo pipefail
here=$(dirname "$0"); out=${OUT:-/tmp/tank}; mkdir -p "$out"
python3 "$here/variants.py" "$out"
dx=$1; avg=$2; shift 2
for n in "$@"; do
  ./build/test/app/ranryu validate hydrostatic --scene "$out/$n.json" --spacing "$dx" --average "$avg" --quiet \
      --json "$out/$n-$dx.json" > "$out/$n-$dx.txt" 2>&1
  grep -E 'interior \(a kernel|floor layer:|rms speed averaged|steps in' "$out/$n-$dx.txt"
done
