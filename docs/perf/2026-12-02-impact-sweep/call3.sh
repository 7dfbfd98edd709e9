#!/usr/bin/env bash
# Call 3 (2026-12-02, evening): the whole GL suite on the H200 with the session's tree (the last engine
# change is 04b48c5's Solver::pressure_sample_offset(), after the suite's last run on dd45ce6).
set -u
scripts/gpu/setup-and-build.sh all > /tmp/b.txt 2>&1 || { tail -30 /tmp/b.txt; exit 1; }
. scripts/gpu/env.sh x
start=$(date +%s)
build/gpu/tests/ranryu_gl_tests > "$OUT/gl-tests.txt" 2>&1; echo "== gl suite rc $?: $(tail -2 "$OUT/gl-tests.txt" | head -1), $(( $(date +%s) - start )) s"
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader >> "$OUT/gl-tests.txt" 2>&1
