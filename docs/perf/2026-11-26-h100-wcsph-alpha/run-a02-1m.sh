#!/usr/bin/env bash
# WCSPH's dam break at 1M with sph.artificial_viscosity 0.2 for 10 s, then the front at a/dx 40 and 80.
cp docs/perf/2026-11-26-h100-chebyshev-default/gpu-var.sh scratch/gpu-var.sh
VARIANTS="dam-break/a02:sph.artificial_viscosity=0.2" SOLVER=wcsph PARTICLES=1000000 FRAMES=600 TAG=1m RUN_TIMEOUT=520 bash scratch/gpu-var.sh
. scripts/gpu/env.sh x
mkdir -p $out/validate
python3 scripts/gpu/scene-at.py dam-break $out/validate/db-a02.json 1000 sph.artificial_viscosity=0.2 > /dev/null
for dx in 0.005 0.0025; do
  timeout 60 $B validate dam-break --solver wcsph --spacing $dx --scene $out/validate/db-a02.json --json $out/validate/wcsph-$dx-a02.json --quiet > $out/validate/wcsph-$dx-a02.txt 2>&1
  grep -E "rms|front|steps in" $out/validate/wcsph-$dx-a02.txt | head -5
done
cd $out && tar czf all.tgz */ device.txt
