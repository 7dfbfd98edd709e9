#!/usr/bin/env bash
# WCSPH's dam break at 1M particles (spacing 0.002) for ten simulated seconds with the plan two frames
# back: its one-frame speed spike at t = 1.28 s (2026-11-26, the plan one frame back) again. Particle
# shading at 640x360, the guard watching. Output: one tar under $OUT.
scripts/gpu/setup-and-build.sh ranryu >/dev/null 2>&1 || { echo build failed; exit 1; }
. scripts/gpu/env.sh x
r=$out/r; mkdir -p $r
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $r/device.txt; date -u >> $r/device.txt
timeout ${RUN_TIMEOUT:-530} $B profile --scene media/scenes/dam-break.json --solver wcsph --spacing 0.002 --frames 600 --warmup 0 \
  --shading particles --size 640x360 --records $r/db-1m.csv > $r/db-1m.txt 2>&1
echo "rc $?"; grep -E 'substeps/frame|fps and|^guard|ranryu: simulation' $r/db-1m.txt | grep -v 'profile: frame'
tail -c 300 $r/db-1m.txt | tr '\r' '\n' | tail -2
tar czf $out/wcsph-1m.tgz -C $out r
