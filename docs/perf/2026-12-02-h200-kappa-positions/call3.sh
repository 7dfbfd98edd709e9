#!/usr/bin/env bash
# Call 3 (2026-12-02): call 2's one failing GL case, the water raster's triangles through the near plane
# (tests/gl/water_raster_test.cpp: seed 359719953, 656 thickness pixels of 19,200 past the bound, 1 %
# allowed), whose NVIDIA bound (5e-5 relative) was fitted on three random boxes. The case now prints each
# map's relative excess (median, 99th percentile, largest); run with that seed and 40 fresh ones.
# (Run twice: the first run's line parsing missed Catch's wrapped lines; its seeds and verdicts are
# in seeds-1.txt, the second run's in seeds.txt.)
set -u
scripts/gpu/setup-and-build.sh ranryu_gl_tests > /tmp/b.txt 2>&1 || { tail -30 /tmp/b.txt; exit 1; }
export __EGL_VENDOR_LIBRARY_FILENAMES=/usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json
t="water raster: triangles through the near plane and far past the guard band give what the clipped draws give"
# The second run: the first run's eight failing seeds, then 32 fresh ones.
failed="359719953 3454533022 3899708543 22701665 2244796974 2090430490 3787750527 2420884595"
for k in $(seq 0 39); do
  seed=$(echo $failed | cut -d' ' -f$((k + 1)) -s)
  [ "$k" -ge 8 ] && seed=$(od -An -N4 -tu4 /dev/urandom | tr -d ' ')
  RANRYU_TEST_SEED=$seed timeout 60 build/gpu/tests/ranryu_gl_tests "$t" > "$OUT/run.txt" 2>&1
  rc=$?
  echo "seed $seed rc $rc $(tr '\n' ' ' < "$OUT/run.txt" | tr -s ' ' | grep -oE '(thickness|sun thickness|sun near): NVIDIA[^,]*, relative excess past 3e-5 m: median [^,]*, 99th percentile [^,]*, largest [0-9.e+-]*' | sed 's/NVIDIA H200.PCIe.SSE2, relative excess past 3e-5 m: //' | tr '\n' ';') $(grep -oE 'beyond the bound [0-9]+' "$OUT/run.txt" | tr '\n' ' ')"
done | tee "$OUT/seeds.txt"
