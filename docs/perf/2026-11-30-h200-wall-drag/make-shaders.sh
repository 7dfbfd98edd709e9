#!/usr/bin/env bash
# Run here, in the repository's root, before a call that needs them (scratch/ travels with the tree):
# the shader folders of this folder's calls, from glsl/ and implicit-drag.patch.
#   scratch/glsl-dragout   the drag implicit and out of (D8)'s force condition (calls 1, 3, 6, 7: their tree)
#   scratch/glsl-explicit  the drag explicit and out of the force condition (call 2 (a), its scratch/v1/glsl)
# and scratch/pairs.py (call 6).
set -eu
here=docs/perf/2026-11-30-h200-wall-drag
mkdir -p scratch
for v in dragout explicit; do
  rm -rf scratch/glsl-$v && cp -r glsl scratch/glsl-$v
  git apply -p2 --directory=scratch/glsl-$v --include="scratch/glsl-$v/sim/*" $here/implicit-drag.patch
  f=scratch/glsl-$v/sim/dfsph/compute_density.comp
  sed -i 's|^        magnitude = length(a + drag);.*|        magnitude = length(a);|' $f
  [ $v = explicit ] && sed -i 's|^        accel\[i\] = vec4(a + (speed > 0.0 .*|        accel[i] = vec4(a + drag, length(sum) + spread_);|' $f
  grep -q "magnitude = length(a);" $f
done
grep -q "accel\[i\] = vec4(a + drag, length(sum)" scratch/glsl-explicit/sim/dfsph/compute_density.comp
cp $here/pairs.py scratch/pairs.py
