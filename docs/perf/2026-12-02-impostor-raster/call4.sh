#!/usr/bin/env bash
# Call 4 (2026-12-02): after the review's mends (the large spheres' box precise, the sub-particles'
# count at the caller's draw offset), the impostors' render tests and the sub-particles' drawing cases on
# the H200, the cloud case also at seed 179907235 (where call 1's draw was 2e-6 off the caster's depth).
set -u
scripts/gpu/setup-and-build.sh all > /tmp/b.txt 2>&1 || { tail -30 /tmp/b.txt; exit 1; }
. scripts/gpu/env.sh x
for t in "render:*" "subparticles: drawn as particles*" "subparticles: a pipeline*"; do
  build/gpu/tests/ranryu_gl_tests "$t" > /tmp/t.txt 2>&1
  echo "== $t rc $?: $(tail -2 /tmp/t.txt | head -1)"
done
RANRYU_TEST_SEED=179907235 build/gpu/tests/ranryu_gl_tests "render: a cloud*" > /tmp/t.txt 2>&1
echo "== cloud at seed 179907235 rc $?: $(tail -2 /tmp/t.txt | head -1)"
