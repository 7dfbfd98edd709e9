#!/usr/bin/env bash
# Builds ranryu with its tests (Debug: GL debug contexts, assertions) and runs them through CTest.
# With no GPU the GL tests run on Mesa's llvmpipe; the window test runs under Xvfb.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
cmake -S . -B build/test -G Ninja -DCMAKE_BUILD_TYPE=Debug >/dev/null
cmake --build build/test
cd build/test
RANRYU_REQUIRE_XVFB=1 RANRYU_REQUIRE_FFMPEG=1 ctest --output-on-failure -j "$(nproc)" "$@"
