#!/usr/bin/env bash
# Call 6 (2026-12-02): the whole GL suite on the H200 with the session's last tree (dd45ce6), the new
# impact cases among its cases.
set -u
scripts/gpu/setup-and-build.sh all > /tmp/b.txt 2>&1 || { tail -30 /tmp/b.txt; exit 1; }
. scripts/gpu/env.sh x
mkdir -p "$OUT/suite"
build/gpu/tests/ranryu_gl_tests > "$OUT/suite/gl-tests.txt" 2>&1; echo "== gl suite rc $?: $(tail -2 "$OUT/suite/gl-tests.txt" | head -1)"
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader >> "$OUT/suite/gl-tests.txt" 2>&1
