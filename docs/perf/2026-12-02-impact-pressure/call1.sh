#!/usr/bin/env bash
# Call 1 (2026-12-02): `ranryu validate impact-pressure` (Lobovsky et al. 2014, docs/VALIDATION.md
# "Impact pressure") at H/dx = 24, 48 and 96 (spacings 0.0125, 0.00625, 0.003125 m: 13,824, 110,592 and
# 884,736 particles) with DFSPH as the dam break ships it (no-slip walls), DFSPH with free-slip walls,
# WCSPH and PBF; then the new test cases on the H200.
set -u
scripts/gpu/setup-and-build.sh all > /tmp/b.txt 2>&1 || { tail -30 /tmp/b.txt; exit 1; }
root=$OUT
OUT=$root/impact RUN_TIMEOUT=200 scripts/gpu/impact-pressure.sh "0.0125 0.00625 0.003125"
. scripts/gpu/env.sh x
build/gpu/tests/ranryu_gl_tests "*Lobovsky*" > "$root/impact/gl-test.txt" 2>&1; echo "== gl test rc $?: $(tail -2 "$root/impact/gl-test.txt" | head -1)"
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > "$root/impact/device.txt" 2>&1
(cd "$root" && tar czf impact.tgz impact && rm -rf impact)
