#!/usr/bin/env bash
# Session 33, call 2: the overlay's own renderer (render::OverlayDraw) on NVIDIA: its GL test, its cost
# at 1920x1080 against the run without it, then the whole GL test suite on this device.
set -u
scripts/gpu/setup-and-build.sh all > $OUT/build.txt 2>&1 || { tail -30 $OUT/build.txt; exit 1; }
grep -i "imgui\|overlay" $OUT/build.txt | head -5
. scripts/gpu/env.sh x
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; date -u
timeout 60 build/gpu/tests/ranryu_gl_tests "[overlay]" 2>&1 | tail -4 | tee $OUT/overlay-test.txt
OUT=$OUT/ov timeout 200 scripts/gpu/overlay.sh "0.00317" 120 20 2>&1 | tail -8
tar czf $OUT/overlay.tgz -C $OUT ov && rm -rf $OUT/ov
start=$(date +%s)
timeout 280 build/gpu/tests/ranryu_gl_tests --durations yes > $OUT/gl-tests.txt 2>&1; echo "gl tests rc $? in $(( $(date +%s) - start )) s"
tail -5 $OUT/gl-tests.txt
grep -B2 -A12 "FAILED" $OUT/gl-tests.txt | head -60
