#!/usr/bin/env bash
# ranryu under AddressSanitizer and UndefinedBehaviorSanitizer (the asan preset, build/asan): the
# CPU (unit) tests, the fuzz corpus of bad scenes and command lines run through the sanitized binary
# (tests/cli/fuzz_test.cpp, from the debug build's test program), and one short headless record of an
# SPH scene with the turbulence force and sub-particles on llvmpipe. Any report fails the run: UBSan
# halts on the first error, ASan on any memory error, LeakSanitizer on any leak outside the GL
# driver (tests/sanitizers/lsan.supp suppresses only Mesa's and LLVM's own).
# scripts/test.sh calls it after the suite. Measured 2026-11-25 on the 2-core Debian 12 machine while
# other builds shared it (load average ~10): the build/asan build from clean took ~13 min of wall time
# for ~4 min of CPU (so ~2-3 min on 2 idle cores), and the three runs 52 s of wall time for 17 s of CPU.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
cmake --preset asan >/dev/null
cmake --build --preset asan                                 # ranryu, ranryu_unit_tests
cmake --build --preset debug --target ranryu_cli_tests      # the fuzz test's driver (no sanitizer needed there)

export ASAN_OPTIONS=detect_leaks=1:check_initialization_order=1:strict_init_order=1:detect_stack_use_after_return=1
export UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1
export LSAN_OPTIONS=suppressions=$root/tests/sanitizers/lsan.supp:print_suppressions=0

echo "sanitize: unit tests"
build/asan/tests/ranryu_unit_tests
# Mesa's EGL vendor library and its DRI driver are preloaded so that they stay mapped until the leak
# check: glvnd and EGL dlclose them at exit, after which LeakSanitizer can neither scan their globals
# (which still hold the driver's long-lived blocks, so those read as leaks) nor name them in a stack
# (so no suppression could match). Mapped, their blocks are reachable and any real leak in them is
# named, and only then suppressed by tests/sanitizers/lsan.supp. ASan's runtime still loads first.
multiarch=$(gcc -print-multiarch 2>/dev/null || echo x86_64-linux-gnu)
preload=libEGL_mesa.so.0
for dri in /usr/lib/$multiarch/dri/swrast_dri.so; do [ -f "$dri" ] && preload="$preload $dri"; done
echo "sanitize: fuzz corpus through build/asan/app/ranryu"
# With Mesa preloaded too: a command that made a context before refusing its input (record checks
# the scene's memory against the device before it makes its folder) must not read as a leak.
LD_PRELOAD="$preload" ASAN_OPTIONS=$ASAN_OPTIONS:verify_asan_link_order=0 \
  RANRYU_TEST_BIN=$root/build/asan/app/ranryu build/test/tests/ranryu_cli_tests "[fuzz]"
echo "sanitize: a short headless record"
out=$(mktemp -d /tmp/ranryu-sanitize-XXXXXX)
trap 'rm -rf "$out"' EXIT
LD_PRELOAD="$preload" ASAN_OPTIONS=$ASAN_OPTIONS:verify_asan_link_order=0 \
  build/asan/app/ranryu record --scene tests/data/scenes/sanitize.json --frames 3 --out "$out/rec" --quiet >/dev/null
test -f "$out/rec/frame_00002.png" && test -f "$out/rec/run.json"
echo "sanitize: clean"
