#!/usr/bin/env bash
# The frame's fastest and densest particles folded from per-workgroup entries (FrameExtreme,
# record_extremes.comp) in place of an index written after an atomicMax: the whole GL and CLI profile
# tests on the NVIDIA driver; the new race case 15 times on this tree and 15 times on the tree before's
# shaders (scratch/old/, a working copy: glsl files of 4c9c54c and a record_extremes.comp that does
# nothing), to show that the case catches the race there; and the dam break at 246k for ten seconds
# (the whole pipeline at 1920x1080) against the last session's call 7 records and frame rate.
set -u
scripts/gpu/setup-and-build.sh all > /tmp/build1.txt 2>&1 || { tail -30 /tmp/build1.txt; exit 1; }
. scripts/gpu/env.sh x
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | tee $OUT/device.txt; date -u | tee -a $OUT/device.txt
timeout 200 build/gpu/tests/ranryu_gl_tests > $OUT/gl-tests.txt 2>&1; echo "gl tests rc $?"; tail -3 $OUT/gl-tests.txt
RANRYU_TEST_BIN=$PWD/build/gpu/app/ranryu timeout 150 build/gpu/tests/ranryu_cli_tests "[profile]" > $OUT/cli-tests.txt 2>&1; echo "cli profile tests rc $?"; tail -3 $OUT/cli-tests.txt
race() {   # $1: label; the race case 15 times, each with a fresh seed
    local fails=0
    for k in $(seq 15); do
        timeout 60 build/gpu/tests/ranryu_gl_tests "guard: the frame's fastest and densest*" > /tmp/race.txt 2>&1 || { fails=$((fails + 1)); grep -m4 -E "seed|FAILED|with expansion" -A1 /tmp/race.txt >> $OUT/race-$1.txt; }
    done
    echo "race case, $1: $fails of 15 runs failed" | tee -a $OUT/race-$1.txt
}
race new
f=$OUT/dam-246k
timeout 100 $B profile --scene dam-break --spacing 0.00317 --size 1920x1080 --frames 600 --warmup 0 --records $f.csv > $f.txt 2>&1
echo "== dam break 246k rc $?"; grep -E "substeps/frame \(|density solve:|fps and real|^record-extremes|^diagnostics|^frame " $f.txt | cut -c1-200
python3 - "$f.csv" docs/perf/2026-12-01-h200-passes-within/call7/dam-246k.csv <<'PY'
import csv, sys
a = list(csv.DictReader(open(sys.argv[1]))); b = list(csv.DictReader(open(sys.argv[2])))
d = {}
for ra, rb in zip(a, b):
    for k in ra:
        if ra[k] != rb[k]: d[k] = d.get(k, 0) + 1
print("records against the last session's call 7:", len(a), "frames; fields that differ (frames):", d or "none")
PY
cp -r scratch/old/glsl/. glsl/
cmake --build build/gpu -j 16 --target ranryu_gl_tests > /tmp/build-old.txt 2>&1 || { tail -30 /tmp/build-old.txt; exit 1; }
race old
