#!/usr/bin/env bash
# The new tests of the passes within passes on the NVIDIA driver (tests/gl/profile_test.cpp,
# tests/gl/dfsph_test.cpp, tests/cli/profile_test.cpp: their last cases), after the review's fixes.
set -u
scripts/gpu/setup-and-build.sh all > /tmp/build3.txt 2>&1 || { tail -30 /tmp/build3.txt; exit 1; }
. scripts/gpu/env.sh x
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | tee $OUT/device.txt; date -u | tee -a $OUT/device.txt
build/gpu/tests/ranryu_gl_tests "profile*","dfsph: each solve's dispatches*" > $OUT/gl-tests.txt 2>&1; echo "gl tests rc $?"; tail -3 $OUT/gl-tests.txt
RANRYU_TEST_BIN=$PWD/build/gpu/app/ranryu build/gpu/tests/ranryu_cli_tests "ranryu profile --detail*" > $OUT/cli-tests.txt 2>&1; echo "cli tests rc $?"; tail -3 $OUT/cli-tests.txt
$B profile --scene dam-break --spacing 0.005 --size 640x360 --frames 60 --warmup 0 --detail > $OUT/dam-64k-detail.txt 2>&1; echo "profile rc $?"
sed -n '/^pass /,/^$/p' $OUT/dam-64k-detail.txt; grep -E "^--detail|^  their|fps and" $OUT/dam-64k-detail.txt
