#!/usr/bin/env bash
# The dam break's ten seconds at 246k with DFSPH (particle shading at 640x360, as docs/PERFORMANCE.md's
# 10 s tables), built from dc51a34 (the plan read the newest record at hand; its sources carried in
# .old/) and from commit c6e48a1 (the record five frames back), on one machine; then WCSPH's dam break at 1M
# to t = 1.5 s, past the moment (t = 1.28 s) where the H100's runs passed one frame over the speed bound.
# Before the call, here: mkdir .old && git archive dc51a34 CMakeLists.txt CMakePresets.json cmake engine glsl
# app media/scenes scripts tests | tar x -C .old (ignored in .git/info/exclude); carry .gl and .old.
scripts/gpu/setup-and-build.sh ranryu >/dev/null 2>&1 || { echo build failed; exit 1; }
. scripts/gpu/env.sh x
cmake -S .old -B build/old -G Ninja -DCMAKE_BUILD_TYPE=Release -DRANRYU_WINDOW=OFF >/dev/null && cmake --build build/old -j 16 --target ranryu >/dev/null || { echo old build failed; exit 1; }
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $out/device2.txt; date -u >> $out/device2.txt
for b in old gpu; do
  build/$b/app/ranryu profile --scene dam-break --solver dfsph --spacing 0.00317 --frames 600 --warmup 0 --shading particles --size 640x360 --quiet > $out/db-246k-10s-$b.txt 2>&1
  grep -E 'substeps/frame|density solve|fps and' $out/db-246k-10s-$b.txt | sed "s/^/$b: /"
done
$B profile --scene dam-break --solver wcsph --spacing 0.002 --frames 90 --warmup 0 --shading particles --size 640x360 --records $out/wcsph-1m-1.5s.csv --quiet > $out/wcsph-1m-1.5s.txt 2>&1
grep -E 'substeps/frame|fps and|guard|spike|unstable' $out/wcsph-1m-1.5s.txt | head
