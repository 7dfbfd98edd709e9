#!/usr/bin/env bash
# On the GPU host, after setup-and-build.sh: DFSPH's boundary rows (docs/DFSPH.md (D9)) against
# Akinci's boundary term (sph.boundary_rows false).
# 1. The tank at rest (`validate hydrostatic`) at 0.00625 m (32 layers, 15k particles) and 0.003125 m
#    (80 layers, 245k particles) with the rows; Akinci's term at 0.00625 m beside them.
# 2. The dam break's cost at about 250k particles (--spacing 0.00317, Fresnel surface, 1920x1080) with
#    and without the rows: `profile` over frames 20-27.
# Writes $OUT/rows-summary.txt (the lines that matter) and rows.tar.gz (every report).
set -uo pipefail
cd "$(dirname "$0")/../.."
out=${OUT:-bench-out}
mkdir -p "$out"
work=/tmp/rows
mkdir -p "$work"
B=build/gpu/app/ranryu
for case in hydrostatic dam-break; do
  for mode in rows akinci; do
    python3 - "$case" "$mode" "$work/$case-$mode.json" <<'PY'
import json, sys
s = json.load(open(f"media/scenes/{sys.argv[1]}.json"))
s.pop("$schema", None)
s["name"] = sys.argv[1] + "-" + sys.argv[2]
s.setdefault("sph", {})["boundary_rows"] = sys.argv[2] == "rows"
if sys.argv[2] != "rows": s["sph"]["eliminate_boundary_rows"] = False   # (D13) needs the rows
json.dump(s, open(sys.argv[3], "w"))
PY
  done
done
run() { local name=$1; shift; local t0=$SECONDS; timeout 300 "$B" "$@" > "$work/$name.txt" 2>&1; local rc=$?;
        echo "== $name (rc $rc, $((SECONDS - t0)) s)"; }
{
  run hydrostatic-rows-0.00625 validate hydrostatic --scene "$work/hydrostatic-rows.json" --spacing 0.00625 --quiet --json "$work/hydrostatic-rows-0.00625.json"
  grep -E "pressure error|floor layer|steps in" "$work/hydrostatic-rows-0.00625.txt"
  run hydrostatic-akinci-0.00625 validate hydrostatic --scene "$work/hydrostatic-akinci.json" --spacing 0.00625 --quiet
  grep -E "pressure error|floor layer|steps in" "$work/hydrostatic-akinci-0.00625.txt"
  run hydrostatic-rows-0.003125 validate hydrostatic --scene "$work/hydrostatic-rows.json" --spacing 0.003125 --quiet --json "$work/hydrostatic-rows-0.003125.json"
  grep -E "particles|pressure error|floor layer|steps in" "$work/hydrostatic-rows-0.003125.txt"
  for mode in rows akinci; do
    scene="$work/dam-break-$mode.json"
    run dam-break-$mode-250k profile --scene "$scene" --spacing 0.00317 --size 1920x1080 --frames 8 --warmup 20 --json "$work/dam-break-$mode-250k.json"
    grep -E "particles|substeps|iterations|dfsph\.|GPU ms|real-time|guard|unstable" "$work/dam-break-$mode-250k.txt" | head -30
  done
} 2>&1 | tee "$out/rows-summary.txt"
tar czf "$out/rows.tar.gz" -C /tmp rows
