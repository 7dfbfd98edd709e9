#!/usr/bin/env bash
# The settled pool's density iterations a frame at about 125k and 512k particles, against the reading of
# "The boundary rows set from the fluid's pressure ...": 97 at 246k and 205 at 1M fit ~N^0.53, which
# predicts about 68 and 143 (a fixed c/h, ~N^(1/3): 77 and 124-164). The dam break as shipped, ten seconds.
set -u
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
scripts/gpu/setup-and-build.sh ranryu > $OUT/build.txt 2>&1 || { tail -30 $OUT/build.txt; exit 1; }
. scripts/gpu/env.sh x
export RUN_TIMEOUT=100
TAG=sizes NS="125000 512000" ETAS=1e-3 scripts/gpu/dfsph-eta.sh 2>&1 | grep -v "why its settings" | tee $OUT/sizes.txt
