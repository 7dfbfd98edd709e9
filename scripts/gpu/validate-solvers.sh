#!/usr/bin/env bash
# On the GPU host, after setup-and-build.sh: the validation cases with each solver at two resolutions
# (docs/VALIDATION.md): the dam break at a/dx = 40 and 80 (free-slip walls, and DFSPH with no-slip
# walls, nu_b = nu), the tank at rest at 0.0125 m and 0.00625 m. Usage:
#     scripts/gpu/validate-solvers.sh ["dfsph wcsph"]
# Each run's JSON and output go to $OUT (or ./bench-out); the error lines are printed.
set -uo pipefail
cd "$(dirname "$0")/../.."
out=${OUT:-bench-out}
mkdir -p "$out"
B=${RANRYU_BIN:-build/gpu/app/ranryu}
solvers=${1:-"dfsph wcsph"}
python3 - "$out/dam-break-no-slip.json" <<'PY'
import json, sys
s = json.load(open("media/scenes/dam-break.json"))
s["sph"]["boundary_viscosity"] = s["sph"]["viscosity"]
json.dump(s, open(sys.argv[1], "w"), indent=1)
PY
run() {   # name, then validate's arguments
  local name=$1; shift
  timeout 300 $B validate "$@" --json "$out/validate-$name.json" > "$out/validate-$name.txt" 2>&1
  echo "== $name (rc $?)"
  grep -E "^(dam-break|hydrostatic|surge|pressure|floor|dfsph|wcsph|ranryu:)" "$out/validate-$name.txt"
}
for s in $solvers; do
  for a in 40:0.005 80:0.0025; do
    run "dam-break-$s-a${a%%:*}" dam-break --solver "$s" --spacing "${a#*:}"
    [ "$s" = dfsph ] && run "dam-break-$s-no-slip-a${a%%:*}" dam-break --scene "$out/dam-break-no-slip.json" --solver "$s" --spacing "${a#*:}"
  done
  for dx in 0.0125 0.00625; do run "hydrostatic-$s-$dx" hydrostatic --solver "$s" --spacing "$dx"; done
done
