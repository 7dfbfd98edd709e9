#!/usr/bin/env bash
# Call 4 (2026-12-02): what the wall drag the pressure cases favour (nu_b = 1e-4, docs/VALIDATION.md
# "Impact pressure") would cost the dam break: DFSPH's ten seconds at about 250k and 1M particles with
# the scene's 1e-3 and with 1e-4, one binary, particles at 640x360 (scripts/gpu/scenes-seconds.sh).
set -u
scripts/gpu/setup-and-build.sh ranryu > /tmp/b.txt 2>&1 || { tail -30 /tmp/b.txt; exit 1; }
root=$OUT
for n in 250000 1000000; do
  for nu in 1e-3 1e-4; do
    OUT=$root/walls/$n-$nu SOLVER=dfsph PARTICLES=$n SCENES=dam-break KEYS="sph.boundary_viscosity=$nu" RUN_TIMEOUT=130 \
      timeout 140 scripts/gpu/scenes-seconds.sh 10 2>&1 | tail -2
    grep -E "^frame \(GPU|fps and real-time|density solve:|^simulation|spikes|stopped" "$root/walls/$n-$nu/dam-break.txt" | head -6
  done
done
(cd "$root" && tar czf walls.tgz walls && rm -rf walls)
