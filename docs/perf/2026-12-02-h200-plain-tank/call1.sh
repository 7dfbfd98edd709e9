#!/usr/bin/env bash
# Call 1 (2026-12-02): the tank at rest with DFSPH's plain solve (plain.json: the bundled hydrostatic scene
# with with_plain_solve()'s keys of tests/gl/validation_test.cpp) at 0.025 and 0.02 m, settled 0.5 s and
# averaged 0.5 s from the lattice, as the GL test runs it: the engine's shaders (head) and three
# reassociations of the kernel's arithmetic (variants/p1-p3.patch: other roundings, so other
# trajectories; copies of glsl/ under scratch/ made on the development machine), then the GL test case.
set -u
scripts/gpu/setup-and-build.sh all > /tmp/b.txt 2>&1 || { tail -30 /tmp/b.txt; exit 1; }
. scripts/gpu/env.sh x
P=docs/perf/2026-12-02-h200-plain-tank
for v in head p1 p2 p3; do
  d=scratch/$v/glsl; [ $v = head ] && d=scratch/base-glsl/glsl
  for dx in 0.025 0.02; do
    echo "== $v $dx"
    timeout 60 $B validate hydrostatic --scene $P/plain.json --spacing $dx --settle 0.5 --average 0.5 --quiet --shader-dir $d 2>&1 \
      | grep -E "floor layer:|floor's pair|interior \(a"
  done
done
timeout 200 build/gpu/tests/ranryu_gl_tests "validate: DFSPH tank at rest with the plain solve*" -s 2>&1 | grep -vE "^\s*$" | tail -60
