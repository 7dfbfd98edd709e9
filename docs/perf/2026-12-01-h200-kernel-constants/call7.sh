#!/usr/bin/env bash
# WCSPH over the surge (frames 20-40) with the whole pipeline at 246k and 1M on the tree with the kernel's
# constants, for the ratio of DFSPH's real-time factor to WCSPH's on one tree; and the plain-solve tank at
# rest's GL case once more (call 6's one failing case).
set -u
scripts/gpu/setup-and-build.sh all > /tmp/build7.txt 2>&1 || { tail -30 /tmp/build7.txt; exit 1; }
. scripts/gpu/env.sh x
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | tee $OUT/device.txt; date -u | tee -a $OUT/device.txt
timeout 90 build/gpu/tests/ranryu_gl_tests "validate: DFSPH tank at rest with the plain solve*" > $OUT/tank-plain.txt 2>&1; echo "tank case rc $?"; grep -E "interior|passed|failed" $OUT/tank-plain.txt | head -4
OUT=$OUT/surge timeout 100 bash scripts/gpu/bench-dfsph.sh "wcsph" "0.00317 0.002" 20 20 | grep -E "^==|fps|^simulation"
(cd $OUT && tar czf surge.tgz surge && rm -rf surge)
