#!/usr/bin/env bash
# The main job: build ranryu (Release, headless and windowed where GLFW exists), record the default
# scene to out/<scene>/ and print the per-pass GPU timing table. Extra arguments go to `ranryu record`
# (e.g. --scene NAME --frames N --size WxH --force).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
cmake -S . -B build/release -G Ninja -DCMAKE_BUILD_TYPE=Release -DRANRYU_TESTS=OFF >/dev/null
cmake --build build/release
exec build/release/app/ranryu record "$@"
