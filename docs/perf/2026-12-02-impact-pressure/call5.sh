#!/usr/bin/env bash
# Call 5 (2026-12-02): both impact cases again after the review's mends (DFSPH's samples at the frame's
# middle, the window's means over time by the trapezoid rule, the probe blind behind the face, H the
# column's lattice depth, Kleefsman's box centred across the tank), every run of calls 1-3 in one binary:
# impact-pressure at H/dx = 24, 48, 96 with DFSPH at nu_b = 1e-3 (as shipped), 0 (free-slip), 1e-5, 1e-4
# and 3e-4, WCSPH and PBF; obstacle-impact at H/dx = 16, 32, 64 with DFSPH at 1e-3, 0 and 1e-4, PBF, and
# WCSPH at the two coarser; then the two GL test cases on the H200. (Call 2's dam-break fronts are not
# touched by the mends.)
set -u
scripts/gpu/setup-and-build.sh all > /tmp/b.txt 2>&1 || { tail -30 /tmp/b.txt; exit 1; }
root=$OUT
CASE=impact-pressure OUT=$root/c5/impact RUN_TIMEOUT=150 scripts/gpu/impact-pressure.sh "0.0125 0.00625 0.003125" \
  "dfsph dfsph-free-slip dfsph-nu-1e-5 dfsph-nu-1e-4 dfsph-nu-3e-4 wcsph pbf"
CASE=obstacle-impact OUT=$root/c5/obstacle RUN_TIMEOUT=150 scripts/gpu/impact-pressure.sh "0.034375 0.0171875" \
  "dfsph dfsph-free-slip dfsph-nu-1e-4 wcsph pbf"
CASE=obstacle-impact OUT=$root/c5/obstacle RUN_TIMEOUT=150 scripts/gpu/impact-pressure.sh "0.00859375" "dfsph dfsph-free-slip dfsph-nu-1e-4 pbf"
. scripts/gpu/env.sh x
build/gpu/tests/ranryu_gl_tests "*Lobovsky*,*Kleefsman*" > "$root/c5/gl-tests.txt" 2>&1; echo "== gl tests rc $?: $(tail -2 "$root/c5/gl-tests.txt" | head -1)"
(cd "$root" && tar czf c5.tgz c5 && rm -rf c5)
