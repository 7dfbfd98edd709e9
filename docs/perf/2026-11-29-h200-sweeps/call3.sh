#!/usr/bin/env bash
# The scene settings' sweep again on today's tree: every bundled SPH scene at its own spacing for 10 s
# with each solver at the script's default factors, and the rule's choices (scripts/scene-settings.py).
scripts/gpu/setup-and-build.sh ranryu >/dev/null 2>&1 || { echo build failed; exit 1; }
. scripts/gpu/env.sh x
mkdir -p $out/ss
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $out/ss/device.txt; date -u >> $out/ss/device.txt
OUT=$out/ss BUDGET_SECONDS=${BUDGET_SECONDS:-470} scripts/gpu/scene-settings.sh 10 | head -60
tar czf $out/ss.tgz -C $out ss && rm -rf $out/ss
