#!/usr/bin/env bash
# The tree as committed with the kernel's constants in SphParams: the whole GL and CLI profile tests on
# the NVIDIA driver; the dam break at 246k for ten seconds with the whole pipeline at 1920x1080 (against
# the last session's records, docs/perf/2026-12-01-h200-extremes/call2/); over the surge (frames 20-40)
# with the whole pipeline, DFSPH at 246k and 1M and PBF at 1M.
set -u
scripts/gpu/setup-and-build.sh all > /tmp/build6.txt 2>&1 || { tail -30 /tmp/build6.txt; exit 1; }
. scripts/gpu/env.sh x
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | tee $OUT/device.txt; date -u | tee -a $OUT/device.txt
timeout 200 build/gpu/tests/ranryu_gl_tests > $OUT/gl-tests.txt 2>&1; echo "gl tests rc $?"; tail -3 $OUT/gl-tests.txt
RANRYU_TEST_BIN=$PWD/build/gpu/app/ranryu timeout 120 build/gpu/tests/ranryu_cli_tests "[profile]" > $OUT/cli-tests.txt 2>&1; echo "cli profile tests rc $?"; tail -3 $OUT/cli-tests.txt
f=$OUT/dam-246k
timeout 60 $B profile --scene dam-break --spacing 0.00317 --size 1920x1080 --frames 600 --warmup 0 --records $f.csv > $f.txt 2>&1
echo "== dam break 246k rc $?"; grep -E "substeps/frame \(|density solve:|fps and real" $f.txt | cut -c1-200
python3 scripts/gpu/compare-records.py $f.csv docs/perf/2026-12-01-h200-extremes/call2/dam-246k.csv
OUT=$OUT/surge timeout 90 bash scripts/gpu/bench-dfsph.sh "dfsph" "0.00317 0.002" 20 20 | grep -E "^==|fps|^simulation|density solve"
OUT=$OUT/surge timeout 40 bash scripts/gpu/bench-dfsph.sh "pbf" "0.002" 20 20 | grep -E "^==|fps|^simulation"
(cd $OUT && tar czf surge.tgz surge && rm -rf surge)
