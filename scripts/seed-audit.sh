#!/usr/bin/env bash
# Runs the GL tests again and again with fresh random seeds, one process at a time under nice, to find
# the rare seeds a derived bound does not cover (tests/support/gl_fixture.h `Random`: each run draws
# new inputs; RANRYU_TEST_SEED=N repeats one). After scripts/test.sh has built build/test.
#     scripts/seed-audit.sh [ROUNDS] [CATCH-SPEC]     e.g. scripts/seed-audit.sh 20 "paddle:*"
# Every round runs each test the spec selects (default: every test the binary lists) once. Each run is
# a line of $OUT/seed-audit.tsv (test, seed, PASS or FAIL, seconds); a failing run's output is kept as
# $OUT/fail-K-SEED.txt, and the command that repeats it is printed. Exits 1 if any run failed.
set -uo pipefail
cd "$(dirname "$0")/.."
bin=${RANRYU_GL_TESTS:-build/test/tests/ranryu_gl_tests}
out=${OUT:-seed-audit}
rounds=${1:-10}
spec=${2:-}
[ -x "$bin" ] || { echo "seed-audit.sh: $bin is not built (scripts/test.sh builds it)" >&2; exit 2; }
mkdir -p "$out"
specs=(); [ -n "$spec" ] && specs=("$spec")
mapfile -t tests < <("$bin" --list-test-names-only "${specs[@]}" | sed '/^$/d')
[ ${#tests[@]} -gt 0 ] || { echo "seed-audit.sh: no test matches '$spec'" >&2; exit 2; }
echo "seed-audit.sh: ${#tests[@]} tests, $rounds rounds, log $out/seed-audit.tsv"
failed=0
for ((r = 1; r <= rounds; ++r)); do
  for k in "${!tests[@]}"; do
    name=${tests[$k]}
    # Catch's test spec: commas and brackets in a name are escaped.
    escaped=$(printf '%s' "$name" | sed -e 's/\\/\\\\/g' -e 's/,/\\,/g' -e 's/\[/\\[/g' -e 's/\]/\\]/g')
    seed=$(od -An -N4 -tu4 /dev/urandom | tr -d ' ')
    start=$(date +%s.%N)
    RANRYU_TEST_SEED=$seed nice -n 19 "$bin" "$escaped" > "$out/run.txt" 2>&1
    rc=$?
    seconds=$(echo "$(date +%s.%N) - $start" | bc)
    verdict=PASS
    if [ $rc -ne 0 ]; then
      verdict=FAIL failed=$((failed + 1))
      mv "$out/run.txt" "$out/fail-$k-$seed.txt"
      printf 'FAIL: RANRYU_TEST_SEED=%s %s "%s"   (output: %s)\n' "$seed" "$bin" "$escaped" "$out/fail-$k-$seed.txt"
    fi
    printf '%s\t%s\t%s\t%.1f\n' "$name" "$seed" "$verdict" "$seconds" >> "$out/seed-audit.tsv"
  done
  echo "round $r of $rounds done: $failed failed so far"
done
rm -f "$out/run.txt"
[ $failed -eq 0 ]
