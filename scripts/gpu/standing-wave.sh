#!/usr/bin/env bash
# On the GPU host, after setup-and-build.sh has built build/gpu: the standing-wave case (the first
# sloshing mode's period and decay against linear theory, docs/VALIDATION.md) as a sweep over the
# three solvers, four spacings and the default time-step factors (docs/SWEEP.md), then its charts.
# Usage:
#     scripts/gpu/standing-wave.sh ["0.0133,0.01,0.005,0.0025"]
# BUDGET_SECONDS (default 300) stops the sweep (the rows done stay; a rerun with RESUME_FROM=FILE, a
# sweep.json that came back, resumes it). Writes sweep.json, sweep.csv, sweep.log and the charts
# (standing-wave-*.png, .svg) to $OUT (or ./bench-out).
. "$(dirname "$0")/env.sh" bench-out
spacings=${1:-0.0133,0.01,0.005,0.0025}
[ -n "${RESUME_FROM:-}" ] && cp "$RESUME_FROM" "$out/sweep.json"
start=$(date +%s)
timeout "${BUDGET_SECONDS:-300}" $B sweep --out "$out" --cases standing-wave --spacings "$spacings" --quiet \
  > "$out/sweep.log" 2>&1
echo "sweep: rc $? after $(( $(date +%s) - start )) s, $(python3 -c "import json,sys; print(len(json.load(open(sys.argv[1]))['rows']))" "$out/sweep.json" 2>/dev/null || echo '?') rows"
python3 scripts/sweep-charts.py "$out" --out "$out/charts" > "$out/charts.log" 2>&1 || cat "$out/charts.log"
for f in "$out"/charts/*; do [ -f "$f" ] && mv "$f" "$out/standing-wave-$(basename "$f")"; done
rmdir "$out/charts" 2>/dev/null
true
