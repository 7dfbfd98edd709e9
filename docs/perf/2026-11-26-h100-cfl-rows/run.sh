#!/usr/bin/env bash
# The dam break's Courant number (sph.cfl, (D8)) with the boundary rows, as shipped otherwise:
# 10 s at 246k and the surge front at a/dx = 40 for 0.5 and 0.6; the first 3 s at 1M for 0.4, 0.5, 0.6.
# Run on the GPU host from the repository root after scripts/gpu/setup-and-build.sh, with OUT set.
. scripts/gpu/env.sh x
o=$OUT
for c in 0.5 0.6; do
  OUT=$o TAG=cfl$c NS=250000 ETAS=1e-4 KEYS="sph.cfl=$c" FRONT_ETAS=1e-4 RUN_TIMEOUT=120 scripts/gpu/dfsph-eta.sh 2>&1 | grep -v "why its" | sed "s/^/cfl $c: /"
done
OUT=$o TAG=cfl0.4-front NS=1000 FRAMES=1 ETAS=1e-4 FRONT_ETAS=1e-4 scripts/gpu/dfsph-eta.sh 2>&1 | grep "front" | sed "s/^/cfl 0.4: /"
for c in 0.4 0.5 0.6; do
  OUT=$o TAG=cfl$c-1m NS=1000000 FRAMES=180 ETAS=1e-4 KEYS="sph.cfl=$c" RUN_TIMEOUT=150 scripts/gpu/dfsph-eta.sh 2>&1 | grep -v "why its" | sed "s/^/cfl $c 1M: /"
done
