#!/usr/bin/env bash
# Session 33, call 5: the unit and CLI tests on NVIDIA (the GL suite passed in call 4).
set -u
scripts/gpu/setup-and-build.sh all > $OUT/build.txt 2>&1 || { tail -30 $OUT/build.txt; exit 1; }
. scripts/gpu/env.sh x
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; date -u
start=$(date +%s)
timeout 60 build/gpu/tests/ranryu_unit_tests -r compact > $OUT/unit-tests.txt 2>&1; echo "unit tests rc $? in $(( $(date +%s) - start )) s"
tail -2 $OUT/unit-tests.txt
start=$(date +%s)
(cd build/gpu/tests && timeout 330 ./ranryu_cli_tests -r compact > $OUT/cli-tests.txt 2>&1); echo "cli tests rc $? in $(( $(date +%s) - start )) s"
grep -v "passed:" $OUT/cli-tests.txt | grep -v "GL message" | cut -c1-600 | tail -30
