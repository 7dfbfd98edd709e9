#!/usr/bin/env bash
# (As run on the device it copied scratch/objects-direct.cpp, engine/gl/objects.cpp with this patch, over the file.)
# Session 33, call 4: the whole GL suite on NVIDIA with the three fixes; then whether a synchronous read of
# the fluid's buffers (the validation cases' energy at the start) slows the run after it: validate
# dam-break with the staged read (as committed) and with a direct glGetBufferSubData of the live buffer.
set -u
scripts/gpu/setup-and-build.sh all > $OUT/build.txt 2>&1 || { tail -30 $OUT/build.txt; exit 1; }
. scripts/gpu/env.sh x
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; date -u
start=$(date +%s)
timeout 200 build/gpu/tests/ranryu_gl_tests -r compact > $OUT/gl-tests.txt 2>&1; echo "gl tests rc $? in $(( $(date +%s) - start )) s"
grep -v "passed:" $OUT/gl-tests.txt | grep -v "GL message" | cut -c1-500 | tail -12
v() { timeout 120 $B validate dam-break --solver dfsph --spacing 0.005 --json $OUT/v-$1.json --quiet > $OUT/v-$1.txt 2>&1; python3 -c "
import json,sys; j=json.load(open('$OUT/v-$1.json')); print('$1', j['particles'], 'particles', j['steps'], 'steps', round(j['wall_seconds'],2), 's wall, rms', round(j['rms_error'],4))"; }
v staged-a; v staged-b
patch -s -p1 < docs/perf/2026-11-30-h200-gl-suite/direct-read.patch && cmake --build build/gpu --target ranryu > /dev/null 2>&1
v direct-a; v direct-b
