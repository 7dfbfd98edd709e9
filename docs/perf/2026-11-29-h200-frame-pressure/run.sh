#!/usr/bin/env bash
# DFSPH's Density.y as the frame's dt-weighted pressure (06cb0f6) on the GPU: the tank at rest as the
# scene sets it at three spacings (what issue 11's bounds read), then the dam break as shipped for ten
# seconds at 246k and 1M particles (what the FramePressure array's 32 B a particle a step costs, against
# docs/perf/2026-11-29-h200-courant/'s 24.3 and 5.2 fps on the tree before it).
scripts/gpu/setup-and-build.sh ranryu >/dev/null 2>&1 || { echo build failed; exit 1; }
. scripts/gpu/env.sh x
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $out/device.txt; date -u >> $out/device.txt
mkdir -p $out/hs
for dx in 0.0125 0.00625 0.003125; do
  t0=$(date +%s)
  timeout 150 $B validate hydrostatic --solver dfsph --spacing $dx --json $out/hs/hs-$dx.json > $out/hs/hs-$dx.txt 2>&1
  echo "== $dx rc $? $(( $(date +%s) - t0 )) s"; grep -E "interior|floor layer|rms speed|steps in|windows" $out/hs/hs-$dx.txt
done
tar czf $out/hs.tgz -C $out hs && rm -rf $out/hs
TAG=db NS="250000 1000000" ETAS=1e-3 RUN_TIMEOUT=170 scripts/gpu/dfsph-eta.sh
