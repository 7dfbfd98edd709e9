#!/usr/bin/env bash
# Session 33, call 8: (D10) restarted for the whole density solve when its peak error grew over an
# iteration (the weight back to 1, plain Jacobi for one iteration, then the Chebyshev ramp from there),
# as shipped and with the wall's drag out of (D8)'s force condition.
set -u
scripts/gpu/setup-and-build.sh ranryu > $OUT/build.txt 2>&1 || { tail -30 $OUT/build.txt; exit 1; }
export RUN_TIMEOUT=125
run() { TAG=$1 NS="$2" ETAS=1e-3 SHADERS=$3 KEYS="" scripts/gpu/dfsph-eta.sh 2>&1 | grep -v "why its settings" | grep -E "==|substeps/frame \(|density solve|fps and|frames" | tee $OUT/$1.txt; }
run solve-restart "250000" scratch/glsl-solve-restart
run dragout-solve-restart "250000" scratch/glsl-dragout-solve-restart
run dragout-solve-restart-1m "1000000" scratch/glsl-dragout-solve-restart
run solve-restart-1m "1000000" scratch/glsl-solve-restart
