#!/usr/bin/env bash
# Call 1 (2026-12-02, evening): the impact cases' sweep on the H200 (docs/SWEEP.md "The impact cases"):
# `ranryu sweep` over solver x spacing x time-step factor, Lobovsky's wall at H/dx = 24, 48, 96 and
# Kleefsman's box at H/dx = 16, 32, each case as its scene ships (DFSPH with the wall drag 1e-3).
set -u
scripts/gpu/setup-and-build.sh ranryu > /tmp/b.txt 2>&1 || { tail -30 /tmp/b.txt; exit 1; }
. scripts/gpu/env.sh x
root=$OUT
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > "$root/device.txt"
start=$(date +%s)
timeout 330 "$B" sweep --out "$root/impact" --cases impact-pressure --solvers dfsph,wcsph,pbf \
  --spacings 0.0125,0.00625,0.003125 --factors 0.5,1,1.5,2 --quiet > "$root/impact.log" 2>&1
echo "== impact rc $? $(( $(date +%s) - start )) s"
start=$(date +%s)
timeout 200 "$B" sweep --out "$root/obstacle" --cases obstacle-impact --solvers dfsph,wcsph,pbf \
  --spacings 0.034375,0.0171875 --factors 0.5,1,1.5,2 --quiet > "$root/obstacle.log" 2>&1
echo "== obstacle rc $? $(( $(date +%s) - start )) s"
tail -3 "$root"/*.log
