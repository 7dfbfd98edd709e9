#!/usr/bin/env bash
# Call 3 (2026-12-02): the impostors' render tests on the H200 after the sub-particles' variant (the
# render cases and the sub-particles' drawing, both rasters), then WCSPH's dam break at 1M for ten
# seconds with alpha = 0.15 and particle shading at 640x360, now drawn by the compute raster: the
# reference of issue 11's ratio, measured (call 1's figure was derived from 2026-12-01's run).
set -u
scripts/gpu/setup-and-build.sh all > /tmp/b.txt 2>&1 || { tail -30 /tmp/b.txt; exit 1; }
. scripts/gpu/env.sh x
root=$OUT
build/gpu/tests/ranryu_gl_tests "render:*" > "$root/render-tests.txt" 2>&1
echo "== render tests rc $?: $(tail -2 "$root/render-tests.txt" | head -1)"
build/gpu/tests/ranryu_gl_tests "subparticles: drawn as particles*" > "$root/subparticle-tests.txt" 2>&1
echo "== sub-particle drawing rc $?: $(tail -2 "$root/subparticle-tests.txt" | head -1)"
python3 scripts/gpu/scene-at.py dam-break "$root/a.json" 1000000 sph.artificial_viscosity=0.15 > /dev/null
timeout 450 "$B" profile --scene "$root/a.json" --solver wcsph --spacing 0.002 --frames 600 --warmup 0 \
  --shading particles --size 640x360 --records "$root/wcsph-1m-a0.15.csv" > "$root/wcsph-1m-a0.15.txt" 2>&1
echo "rc $?"; grep -E 'substeps/frame \(|fps and|^guard|ranryu: simulation|^(density|forces|integrate|draw-particles|frame) ' "$root/wcsph-1m-a0.15.txt"
(cd "$root" && tar czf runs.tgz render-tests.txt subparticle-tests.txt a.json wcsph-1m-a0.15.* && rm -f render-tests.txt subparticle-tests.txt a.json wcsph-1m-a0.15.*)
