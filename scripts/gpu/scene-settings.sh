#!/usr/bin/env bash
# On the GPU host, after setup-and-build.sh has built build/gpu (this script builds nothing): every
# bundled SPH scene at its own spacing for SECONDS simulated seconds with each solver at a few
# time-step factors (`ranryu sweep`'s scene cases, docs/SWEEP.md "Scene cases"), then the rule that
# picks each scene's cheapest sound setting (scripts/scene-settings.py, docs/SWEEP.md "Choosing a
# scene's settings"). Usage:
#     scripts/gpu/scene-settings.sh [seconds]        # default 10
#     scripts/gpu/scene-settings.sh smoke            # a check of the script on llvmpipe: 0.1 s a row at spacing 0.04
# The grid (one sweep a scene and solver, scene by scene, into one folder):
#   DFSPH_FACTORS  default "1 1.5 2 2.5"  (2.5 is the largest a scene file can hold: sph.cfl <= 1; 2 for
#                  the dam break, whose sph.dfsph_cfl of 0.5 is DFSPH's Courant number)
#   WCSPH_FACTORS  default "1 1.5 2 2.5"
#   PBF_FACTORS    default "0.25 0.5 1 2" (16, 8, 4 and 2 substeps a frame of the scenes' 4 iterations)
#   SOLVERS        default "pbf dfsph wcsph" (the order each scene runs them in)
# BUDGET_SECONDS (default 360) bounds the whole sweep: a sweep started later is skipped and one
# running at the deadline is stopped (the rows done stay), and the rule is applied to the rows
# there are; the missing ones are listed. RESUME_FROM=FILE (a sweep.json that came back from an
# earlier call) is copied in first, so that its rows are not run again (the sweep resumes).
# AT_SCALE="DIR ..." (sweeps of the same scene cases at the sizes the scenes are run at, e.g.
#     ranryu sweep --cases scene:drop --spacings 0.00454,0.00286 --seconds 10 --out DIR
# at about 250k and 1M particles, scripts/gpu/scene-at.py giving the spacings) makes the rule choose
# only settings that are sound there too (scene-settings.py --at-scale).
# Writes to $OUT (or ./bench-out), six files: sweep.json and sweep.csv (the rows), sweep.log (every
# sweep's output), scene-settings.txt and scene-settings.json (the choices, with the keys to merge
# into each scene file's "sph" in media/scenes/), and summary.txt (the grid, the time taken and
# what was not run).
. "$(dirname "$0")/env.sh" bench-out
seconds=${1:-10}
spacing=()
if [ "$seconds" = smoke ]; then
  seconds=0.1 spacing=(--spacings 0.04)
  : "${DFSPH_FACTORS:=1}" "${WCSPH_FACTORS:=1}" "${PBF_FACTORS:=1}"
fi
declare -A factors=([dfsph]=${DFSPH_FACTORS:-1 1.5 2 2.5} [wcsph]=${WCSPH_FACTORS:-1 1.5 2 2.5} [pbf]=${PBF_FACTORS:-0.25 0.5 1 2})
solvers=${SOLVERS:-pbf dfsph wcsph}
budget=${BUDGET_SECONDS:-360}
if [ -n "${RESUME_FROM:-}" ]; then
  [ -f "$RESUME_FROM" ] || { echo "scene-settings.sh: RESUME_FROM=$RESUME_FROM: no such file" >&2; exit 2; }
  cp "$RESUME_FROM" "$out/sweep.json"
fi
# The scene cases, in `ranryu scenes` order: every bundled SPH scene.
scenes=$($B sweep --cases scenes --solvers dfsph --factors 1 --list | sed -E 's|^[0-9]+ scene:([^/]+)/.*|\1|')
[ -n "$scenes" ] || { echo "scene-settings.sh: $B lists no scene cases" >&2; exit 1; }
start=$(date +%s)
deadline=$((start + budget))
: > "$out/sweep.log"
skipped=()
for scene in $scenes; do
  for s in $solvers; do
    left=$((deadline - $(date +%s)))
    if [ "$left" -le 0 ]; then skipped+=("scene:$scene $s"); continue; fi
    # SIGTERM at the deadline: the sweep stops the row in flight and keeps the rows written.
    timeout -s TERM "$left" $B sweep --cases "scene:$scene" --solvers "$s" --factors "$(echo ${factors[$s]} | tr ' ' ,)" \
      "${spacing[@]}" --seconds "$seconds" --quiet --out "$out" >> "$out/sweep.log" 2>&1
    rc=$?
    echo "== scene:$scene $s (factors ${factors[$s]}): rc $rc, $(( $(date +%s) - start )) s so far" | tee -a "$out/sweep.log"
    [ $rc = 124 ] && skipped+=("scene:$scene $s (stopped at the deadline)")
  done
done
took=$(( $(date +%s) - start ))
python3 scripts/scene-settings.py "$out" ${AT_SCALE:+--at-scale $AT_SCALE} --seconds "$seconds" --json "$out/scene-settings.json" \
  > "$out/scene-settings.txt" 2>&1
rc=$?
{
  echo "scripts/gpu/scene-settings.sh: $seconds s a row, scenes: $(echo $scenes), solvers: $solvers"
  for s in $solvers; do echo "  $s factors: ${factors[$s]}"; done
  echo "device: $(nvidia-smi --query-gpu=name,driver_version --format=csv,noheader 2>/dev/null || echo 'no nvidia-smi')"
  echo "sweeps took $took s (budget $budget s); rows: $(python3 -c "import json,sys; print(len(json.load(open(sys.argv[1]))['rows']))" "$out/sweep.json" 2>/dev/null || echo none)"
  if [ ${#skipped[@]} -gt 0 ]; then
    echo "not run or cut short (run again with RESUME_FROM=<this sweep.json> for the rest):"
    printf '  %s\n' "${skipped[@]}"
  fi
  echo "scene-settings.py: rc $rc"
} > "$out/summary.txt"
cat "$out/summary.txt" "$out/scene-settings.txt"
