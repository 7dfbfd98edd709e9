#!/usr/bin/env bash
# Session 33, call 3: the three GL tests that fail on NVIDIA (compression meter, PBF's recorded largest
# density, the water raster's 60 m box), with diagnostics.
set -u
scripts/gpu/setup-and-build.sh ranryu_gl_tests > $OUT/build.txt 2>&1 || { tail -30 $OUT/build.txt; exit 1; }
. scripts/gpu/env.sh x
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; date -u
T=build/gpu/tests/ranryu_gl_tests
timeout 100 $T "[.diag]" 2>&1 | grep diag | cut -c1-700
for t in "validation: the GPU's mean compression equals*" \
         "pbf: the prediction*" \
         "water raster: triangles through the near plane*"; do
  timeout 100 $T "$t" -r compact 2>&1 | grep -v "passed:" | cut -c1-600 | head -12
done
