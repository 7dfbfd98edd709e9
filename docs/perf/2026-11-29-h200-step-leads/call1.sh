#!/usr/bin/env bash
# The variants: the patches in this folder (sgred.patch, the proportional cut of docs/perf/2026-11-29-dfsph-courant-one/controller/proportional/proportional.patch, vrel.patch, markread.patch) applied to a copy of glsl/ of c24e95f in scratch/NAME/glsl; vreli is vrel with "#define VREL_ISOLATED" before compute_density.comp's include of dfsph.glsl; scratch/base-glsl is `git archive HEAD glsl`.
# Call 1 (2026-11-30): the proportional step cut at lambda 0.75 over 10 s at 246k and 1M against the
# shipped dam break, and the residual pass's subgroup reduction against HEAD's at fixed iterations.
set -u
[ -d .gl ] || { echo "no .gl"; exit 2; }
scripts/gpu/setup-and-build.sh ranryu > $OUT/build.txt 2>&1 || { tail -30 $OUT/build.txt; exit 1; }
tail -1 $OUT/build.txt
export RUN_TIMEOUT=200
VARIANTS="head sgred" COUNTS="246078 1000000" scripts/gpu/iteration-bench.sh 2>&1 | tee $OUT/bench.txt
TAG=shipped NS="250000 1000000" ETAS=1e-3 scripts/gpu/dfsph-eta.sh 2>&1 | tee $OUT/shipped.txt
TAG=prop NS="250000 1000000" ETAS=1e-3 KEYS="sph.dfsph_cfl=0.75 sph.force_factor=0.375 sph.max_time_step=0.0075" \
  SHADERS=scratch/prop/glsl scripts/gpu/dfsph-eta.sh 2>&1 | tee $OUT/prop.txt
