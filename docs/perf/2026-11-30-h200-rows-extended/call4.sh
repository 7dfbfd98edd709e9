#!/usr/bin/env bash
# The density solve's peak bound loosened (sph.max_particle_density_error 0.015 and 0.02 against the
# shipped 0.01): in the settled pool the peak bound decides the solves (the median frame's peak at 0.99 %,
# the mean at 0.021 % of the 0.1 % allowed, at 1M); the dam break ten seconds at about 250k and 1M.
set -u
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
scripts/gpu/setup-and-build.sh ranryu > $OUT/build.txt 2>&1 || { tail -30 $OUT/build.txt; exit 1; }
. scripts/gpu/env.sh x
export RUN_TIMEOUT=150
for p in 0.02 0.015; do
  TAG=peak-$p KEYS="sph.max_particle_density_error=$p" NS="250000 1000000" ETAS=1e-3 scripts/gpu/dfsph-eta.sh 2>&1 | grep -v "why its settings" | tee $OUT/peak-$p.txt
done
