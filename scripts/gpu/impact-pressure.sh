#!/usr/bin/env bash
# On the GPU host, after setup-and-build.sh has built build/gpu: `ranryu validate impact-pressure`
# (Lobovsky et al. 2014, docs/VALIDATION.md "Impact pressure") at each spacing with each solver, and
# DFSPH again with free-slip walls (the case's scene, media/validation/impact-pressure.json, with
# sph.boundary_viscosity 0). Usage:
#     scripts/gpu/impact-pressure.sh ["0.0125 0.00625 0.003125"] ["dfsph dfsph-free-slip wcsph pbf"]
# Writes NAME-SPACING.txt (the printed table) and .json (the series) to $OUT (or ./bench-out), and a
# line a run here. RUN_TIMEOUT (default 300 s) bounds each run.
. "$(dirname "$0")/env.sh" bench-out
spacings=${1:-0.0125 0.00625 0.003125}
runs=${2:-dfsph dfsph-free-slip wcsph pbf}
python3 - "$out/free-slip.json" <<'PY'
import json, sys
s = json.load(open("media/validation/impact-pressure.json"))
s["name"] += "-free-slip"
s["sph"]["boundary_viscosity"] = 0.0
s["sph"]["why"] = "The case's scene with free-slip walls (scripts/gpu/impact-pressure.sh)."
s.pop("$schema", None)
json.dump(s, open(sys.argv[1], "w"), indent=1)
PY
for dx in $spacings; do
  for run in $runs; do
    case $run in
      dfsph-free-slip) args=(--scene "$out/free-slip.json") ;;
      *) args=(--solver "$run") ;;
    esac
    start=$(date +%s)
    timeout "${RUN_TIMEOUT:-300}" "$B" validate impact-pressure "${args[@]}" --spacing "$dx" --quiet --json "$out/$run-$dx.json" \
      > "$out/$run-$dx.txt" 2>&1
    rc=$?
    echo "== $run dx $dx: rc $rc, $(( $(date +%s) - start )) s; $(grep -E '^ +P[134] ' "$out/$run-$dx.txt" | tr -s ' ' | tr '\n' '|')"
  done
done
