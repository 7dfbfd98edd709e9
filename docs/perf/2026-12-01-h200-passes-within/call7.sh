#!/usr/bin/env bash
# The Solve block of correct_pressure.comp made not coherent (call 5's `nocoh`; call 6 ran with the Step block of
# fluid.glsl too, `nocoh2`, and a GL test failed): the whole GL test program and the CLI profile tests on the NVIDIA driver, where `coherent`
# changes the code (llvmpipe ignores it), and the dam break at 246k for ten seconds (the whole pipeline at
# 1920x1080) against call 1's run of the tree before.
set -u
scripts/gpu/setup-and-build.sh all > /tmp/build6.txt 2>&1 || { tail -30 /tmp/build6.txt; exit 1; }
. scripts/gpu/env.sh x
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | tee $OUT/device.txt; date -u | tee -a $OUT/device.txt
timeout 200 build/gpu/tests/ranryu_gl_tests > $OUT/gl-tests.txt 2>&1; echo "gl tests rc $?"; tail -3 $OUT/gl-tests.txt
RANRYU_TEST_BIN=$PWD/build/gpu/app/ranryu timeout 150 build/gpu/tests/ranryu_cli_tests "[profile]" > $OUT/cli-tests.txt 2>&1; echo "cli profile tests rc $?"; tail -3 $OUT/cli-tests.txt
f=$OUT/dam-246k
timeout 100 $B profile --scene dam-break --spacing 0.00317 --size 1920x1080 --frames 600 --warmup 0 --records $f.csv > $f.txt 2>&1
echo "== dam break 246k rc $?"; grep -E "substeps/frame \(|density solve:|fps and real|^dfsph\.pressure\.solve|^frame " $f.txt | cut -c1-200
python3 - "$f.csv" docs/perf/2026-12-01-h200-passes-within/call1/dam-246k.csv <<'PY'
import csv, sys
a = list(csv.DictReader(open(sys.argv[1]))); b = list(csv.DictReader(open(sys.argv[2])))
d = {}
for ra, rb in zip(a, b):
    for k in ra:
        if ra[k] != rb[k]: d[k] = d.get(k, 0) + 1
print("records against call 1's:", len(a), "frames; fields that differ (frames):", d or "none")
PY
