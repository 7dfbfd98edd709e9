#!/usr/bin/env bash
# Call 3 (2026-12-02): `ranryu validate obstacle-impact` (Kleefsman et al. 2005, SPHERIC test 2;
# docs/VALIDATION.md "Impact pressure") at H/dx = 16, 32 and 64 (spacings 0.034375, 0.0171875 and
# 0.00859375 m) with DFSPH as the case ships (nu_b = 1e-3), free-slip and at nu_b = 1e-4, and PBF; WCSPH
# at the two coarser (its run at 1M would take minutes); then the new GL test case on the H200.
set -u
scripts/gpu/setup-and-build.sh all > /tmp/b.txt 2>&1 || { tail -30 /tmp/b.txt; exit 1; }
root=$OUT
export CASE=obstacle-impact
OUT=$root/obstacle RUN_TIMEOUT=150 scripts/gpu/impact-pressure.sh "0.034375 0.0171875" "dfsph dfsph-free-slip dfsph-nu-1e-4 wcsph pbf"
OUT=$root/obstacle RUN_TIMEOUT=150 scripts/gpu/impact-pressure.sh "0.00859375" "dfsph dfsph-free-slip dfsph-nu-1e-4 pbf"
. scripts/gpu/env.sh x
build/gpu/tests/ranryu_gl_tests "*Kleefsman*" > "$root/obstacle/gl-test.txt" 2>&1; echo "== gl test rc $?: $(tail -2 "$root/obstacle/gl-test.txt" | head -1)"
(cd "$root" && tar czf obstacle.tgz obstacle && rm -rf obstacle)
