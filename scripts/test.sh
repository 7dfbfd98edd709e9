#!/usr/bin/env bash
# Builds ranryu with its tests (Debug: GL debug contexts, assertions; the debug preset, build/test)
# and runs them through CTest. With no GPU the GL tests run on Mesa's llvmpipe; the window test runs
# under Xvfb. Then, on a whole run (no arguments; RANRYU_SANITIZE_RUN=0 skips it), the CPU tests, the
# fuzz corpus and a short headless record again under AddressSanitizer and UBSan (scripts/sanitize.sh).
# Arguments go to ctest (e.g. -R '^unit:').
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
cmake --preset debug >/dev/null
cmake --build --preset debug
(cd build/test && RANRYU_REQUIRE_XVFB=1 RANRYU_REQUIRE_FFMPEG=1 RANRYU_REQUIRE_MATPLOTLIB=1 ctest --output-on-failure -j "$(nproc)" "$@")
if [ $# -eq 0 ] && [ "${RANRYU_SANITIZE_RUN:-1}" != 0 ]; then
  scripts/sanitize.sh
fi
