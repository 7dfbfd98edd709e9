#!/usr/bin/env bash
# The variants: the patches in this folder (sgred.patch, the proportional cut of docs/perf/2026-11-29-dfsph-courant-one/controller/proportional/proportional.patch, vrel.patch, markread.patch) applied to a copy of glsl/ of c24e95f in scratch/NAME/glsl; vreli is vrel with "#define VREL_ISOLATED" before compute_density.comp's include of dfsph.glsl; scratch/base-glsl is `git archive HEAD glsl`.
# Call 2: DFSPH's CFL step on the largest pair approach speed (the density pass's walk) instead of the
# fastest particle: vrel (isolated particles free), vreli (isolated particles count their speed).
set -u
scripts/gpu/setup-and-build.sh ranryu > $OUT/build.txt 2>&1 || { tail -30 $OUT/build.txt; exit 1; }
. scripts/gpu/env.sh x
mkdir -p $OUT/surge $OUT/front
for v in shipped vrel vreli; do
  sd=""; [ $v != shipped ] && sd="--shader-dir scratch/$v/glsl"
  timeout 120 $B profile --scene dam-break --spacing 0.00317 --size 1920x1080 --frames 20 --warmup 20 $sd --records $OUT/surge/$v.csv > $OUT/surge/$v.txt 2>&1
  echo "== surge 246k $v rc $?"; grep -E "^simulation|density solve|fps and|^guard|frame \(GPU" $OUT/surge/$v.txt
  timeout 100 $B validate dam-break --solver dfsph --spacing 0.005 $sd --json $OUT/front/$v.json --quiet > $OUT/front/$v.txt 2>&1
  echo "== front a/dx=40 $v rc $?"; grep -iE "error|steps" $OUT/front/$v.txt | head -4
done
export RUN_TIMEOUT=200
for v in vrel vreli; do
  TAG=$v NS="250000 1000000" ETAS=1e-3 SHADERS=scratch/$v/glsl scripts/gpu/dfsph-eta.sh 2>&1 | grep -v "why its settings" | tee $OUT/$v.txt
done
