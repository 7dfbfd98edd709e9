#!/usr/bin/env bash
# Call 2 (2026-12-02): the GL suite on the H200 on the tree with the plain solve's bounds (1aad097 and after).
set -u
scripts/gpu/setup-and-build.sh all > /tmp/b.txt 2>&1 || { tail -30 /tmp/b.txt; exit 1; }
. scripts/gpu/env.sh x
{ nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; date -u; git log --oneline -1 2>/dev/null; } | tee $OUT/gl-suite.txt
timeout 400 build/gpu/tests/ranryu_gl_tests 2>&1 | tail -40 | tee -a $OUT/gl-suite.txt
