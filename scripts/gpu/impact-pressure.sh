#!/usr/bin/env bash
# On the GPU host, after setup-and-build.sh has built build/gpu: `ranryu validate CASE` for the impact
# cases (impact-pressure: Lobovsky et al. 2014; obstacle-impact: Kleefsman et al. 2005; docs/VALIDATION.md
# "Impact pressure") at each spacing with each run. Usage:
#     [CASE=impact-pressure] scripts/gpu/impact-pressure.sh ["0.0125 0.00625 0.003125"] ["dfsph dfsph-free-slip wcsph pbf"]
# A run is a solver (dfsph, wcsph, pbf: the case's scene as it is), dfsph-free-slip (DFSPH with
# sph.boundary_viscosity 0) or dfsph-nu-VALUE (DFSPH with sph.boundary_viscosity VALUE), the scene being
# the case's own (media/validation/impact-pressure.json, obstacle-impact.json). Writes RUN-SPACING.txt (the printed table) and .json (the series) to $OUT
# (or ./bench-out), and a line a run here. RUN_TIMEOUT (default 300 s) bounds each run.
. "$(dirname "$0")/env.sh" bench-out
case_name=${CASE:-impact-pressure}
spacings=${1:-0.0125 0.00625 0.003125}
runs=${2:-dfsph dfsph-free-slip wcsph pbf}
for dx in $spacings; do
  for run in $runs; do
    case $run in
      dfsph-free-slip | dfsph-nu-*)
        nu=0
        [ "$run" != dfsph-free-slip ] && nu=${run#dfsph-nu-}
        python3 - "$case_name" "$nu" "$out/$run.json.scene" <<'PY'
import json, sys
case, nu, path = sys.argv[1], float(sys.argv[2]), sys.argv[3]
s = json.load(open(f"media/validation/{case}.json"))
s["name"] += "-nu-%g" % nu
s["sph"]["boundary_viscosity"] = nu
s["sph"]["why"] = "The case's scene with sph.boundary_viscosity %g (scripts/gpu/impact-pressure.sh)." % nu
s.pop("$schema", None)
json.dump(s, open(path, "w"), indent=1)
PY
        args=(--scene "$out/$run.json.scene") ;;
      *) args=(--solver "$run") ;;
    esac
    start=$(date +%s)
    timeout "${RUN_TIMEOUT:-300}" "$B" validate "$case_name" "${args[@]}" --spacing "$dx" --quiet --json "$out/$run-$dx.json" \
      > "$out/$run-$dx.txt" 2>&1
    rc=$?
    echo "== $case_name $run dx $dx: rc $rc, $(( $(date +%s) - start )) s; $(grep -E '^ +P[0-9] ' "$out/$run-$dx.txt" | tr -s ' ' | tr '\n' '|')"
  done
done
