#!/usr/bin/env bash
# Session 33, call 6: does NVIDIA recompile shaders "based on GL state" in the frame loop of a real run,
# and in which frames? The dam break with each shading, a GL debug context (--gl-debug prints the
# driver's messages), progress lines each frame.
set -u
scripts/gpu/setup-and-build.sh ranryu > $OUT/build.txt 2>&1 || { tail -30 $OUT/build.txt; exit 1; }
. scripts/gpu/env.sh x
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; date -u
for sh in water fresnel particles; do
  echo "== $sh"
  RANRYU_PROGRESS_SECONDS=0 timeout 120 $B profile --scene dam-break --shading $sh --size 640x360 --frames 6 --warmup 0 --gl-debug 2>&1 \
    | grep -E "GL message|ranryu profile: frame" | sed 's/Program\/shader state performance warning: //' | cut -c1-220 | head -30
done
echo "== turbulent jet (sub-particles, spray)"
RANRYU_PROGRESS_SECONDS=0 timeout 120 $B profile --scene turbulent-jet --size 640x360 --frames 6 --warmup 0 --gl-debug 2>&1 \
  | grep -E "GL message|ranryu profile: frame" | cut -c1-220 | head -30
