#!/usr/bin/env bash
# Call 6: the tree as committed (WCSPH's forces pass and PBF's correction with their sums folded): WCSPH
# over the surge (frames 20-40) with the whole pipeline at 246k and 1M, PBF at 1M (scripts/gpu/bench-dfsph.sh,
# as "Side by side as shipped" and call 7 of ../2026-12-01-h200-kernel-constants/ ran them); then the GL
# tests and the CLI profile tests on the NVIDIA driver.
set -u
scripts/gpu/setup-and-build.sh all > /tmp/b.txt 2>&1 || { tail -30 /tmp/b.txt; exit 1; }
. scripts/gpu/env.sh x
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | tee $OUT/device.txt; date -u | tee -a $OUT/device.txt
OUT=/tmp/surge timeout 100 bash scripts/gpu/bench-dfsph.sh "wcsph" "0.00317 0.002" 20 20 | grep -E "^==|fps|^simulation"
OUT=/tmp/surge timeout 40 bash scripts/gpu/bench-dfsph.sh "pbf" "0.002" 20 20 | grep -E "^==|fps|^simulation"
tar czf $OUT/surge.tgz -C /tmp surge
timeout 220 build/gpu/tests/ranryu_gl_tests -r compact > $OUT/gl-tests.txt 2>&1; echo "gl tests rc $?"; grep -E "failed:" $OUT/gl-tests.txt | cut -c1-300 | head; tail -2 $OUT/gl-tests.txt
RANRYU_TEST_BIN=$PWD/build/gpu/app/ranryu timeout 60 build/gpu/tests/ranryu_cli_tests "[profile]" > $OUT/cli-tests.txt 2>&1; echo "cli profile tests rc $?"; tail -2 $OUT/cli-tests.txt
