#!/usr/bin/env bash
# Call 7: the tank at rest with DFSPH for ten seconds at about 250k (call 1's run stopped at frame 450 by
# its 120 s bound), the guard watching; DFSPH's shaders are call 1's.
set -u
scripts/gpu/setup-and-build.sh ranryu > /tmp/b.txt 2>&1 || { tail -30 /tmp/b.txt; exit 1; }
. scripts/gpu/env.sh x
{ nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; date -u; } | tee $OUT/device.txt
OUT=/tmp/s250k SOLVER=dfsph PARTICLES=250000 SCENES=hydrostatic RUN_TIMEOUT=215 scripts/gpu/scenes-seconds.sh 10
tar czf $OUT/s250k.tgz -C /tmp s250k
