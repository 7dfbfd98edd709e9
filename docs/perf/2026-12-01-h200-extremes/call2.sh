#!/usr/bin/env bash
# The tree as committed (the frame's maxima kept live by atomicMax again, beside the entries: call 1's
# tree had them set by the fold alone, and two GL cases that read them between passes failed): the whole
# GL and CLI profile tests on the NVIDIA driver, the race case 15 times, the dam break at 246k for ten
# seconds with the whole pipeline at 1920x1080 (against call 1's and the last session's call 7's
# records), and at 1M for ten seconds with particle shading at 640x360 (issue 11's 1M figure, last
# measured before the residual pass's block lost `coherent`).
set -u
scripts/gpu/setup-and-build.sh all > /tmp/build2.txt 2>&1 || { tail -30 /tmp/build2.txt; exit 1; }
. scripts/gpu/env.sh x
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | tee $OUT/device.txt; date -u | tee -a $OUT/device.txt
timeout 200 build/gpu/tests/ranryu_gl_tests > $OUT/gl-tests.txt 2>&1; echo "gl tests rc $?"; tail -3 $OUT/gl-tests.txt
RANRYU_TEST_BIN=$PWD/build/gpu/app/ranryu timeout 150 build/gpu/tests/ranryu_cli_tests "[profile]" > $OUT/cli-tests.txt 2>&1; echo "cli profile tests rc $?"; tail -3 $OUT/cli-tests.txt
fails=0
for k in $(seq 15); do
    timeout 60 build/gpu/tests/ranryu_gl_tests "guard: the frame's fastest and densest*" > /tmp/race.txt 2>&1 || { fails=$((fails + 1)); grep -m4 -E "seed|FAILED" -A1 /tmp/race.txt >> $OUT/race.txt; }
done
echo "race case: $fails of 15 runs failed" | tee -a $OUT/race.txt
f=$OUT/dam-246k
timeout 100 $B profile --scene dam-break --spacing 0.00317 --size 1920x1080 --frames 600 --warmup 0 --records $f.csv > $f.txt 2>&1
echo "== dam break 246k rc $?"; grep -E "substeps/frame \(|density solve:|fps and real|^record-extremes|^frame " $f.txt | cut -c1-200
python3 scripts/gpu/compare-records.py $f.csv docs/perf/2026-12-01-h200-extremes/call1/dam-246k.csv
python3 scripts/gpu/compare-records.py $f.csv docs/perf/2026-12-01-h200-passes-within/call7/dam-246k.csv
f=$OUT/dam-1m
timeout 200 $B profile --scene dam-break --spacing 0.002 --shading particles --size 640x360 --frames 600 --warmup 0 --records $f.csv > $f.txt 2>&1
echo "== dam break 1M rc $?"; grep -E "particles,|substeps/frame \(|density solve:|fps and real|^frame " $f.txt | cut -c1-200
