#!/usr/bin/env bash
# The variants: the patches in this folder (sgred.patch, the proportional cut of docs/perf/2026-11-29-dfsph-courant-one/controller/proportional/proportional.patch, vrel.patch, markread.patch) applied to a copy of glsl/ of c24e95f in scratch/NAME/glsl; vreli is vrel with "#define VREL_ISOLATED" before compute_density.comp's include of dfsph.glsl; scratch/base-glsl is `git archive HEAD glsl`.
# Call 3: the density pass's boundary marks read before their exchange (markread) against HEAD's.
set -u
scripts/gpu/setup-and-build.sh ranryu > $OUT/build.txt 2>&1 || { tail -30 $OUT/build.txt; exit 1; }
VARIANTS="head markread" TEN_S_VARIANTS="head markread" COUNTS="246078 1000000" scripts/gpu/iteration-bench.sh 2>&1 | grep -v "why its settings" | tee $OUT/bench.txt
