#!/usr/bin/env bash
# The main job: build ranryu (Release, headless and windowed where GLFW exists), record the dam break
# (0.4 s of simulated time, the collapse reaching the far wall) to out/dam-break/, and to
# out/dam-break.mp4 when ffmpeg is installed, and print the per-pass GPU timing table. About a minute
# on llvmpipe with no GPU. Arguments replace the defaults and go to `ranryu record` (e.g. --scene
# NAME --frames N --size WxH --spacing DX --force --video FILE).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
cmake --preset release >/dev/null   # build/release: Release, no tests (CMakePresets.json)
cmake --build --preset release
if [ $# -eq 0 ]; then
  set -- --scene dam-break --frames 24 --force
  if command -v ffmpeg >/dev/null; then set -- "$@" --video out/dam-break.mp4; fi
fi
exec build/release/app/ranryu record "$@"
