#!/usr/bin/env bash
# A diagnostic of the bytes a neighbour: the accelerate pass reads kappa_j (4 bytes) a neighbour, the
# residual pass a_j as a vec4 (16). First tried (this script with VARIANTS="current xonly current"): `xonly`
# (`call4/xonly.patch`) made the residual pass read a_j's x alone, but its wrong sums went non-finite at
# step 37 and its 1M run did not end within the call (call4/first/). Then `accel16` (`call4/accel16.patch`):
# the accelerate pass reads each neighbour's Density vec4 besides its kappa, 16 bytes more, its sums
# unchanged: what it adds to the accelerate pass is what 16 bytes a neighbour cost, against the residual
# pass's excess. Both variants were written under the untracked scratch/ and not kept.
set -u
scripts/gpu/setup-and-build.sh ranryu > /tmp/build4.txt 2>&1 || { tail -30 /tmp/build4.txt; exit 1; }
VARIANTS="${VARIANTS:-current accel16 current}" bash scripts/gpu/iteration-bench.sh 2>&1 | grep -E "^==|dfsph\.pressure\.solve|density solve"
