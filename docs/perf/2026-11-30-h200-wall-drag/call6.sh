#!/usr/bin/env bash
# Call 6: are the settled pool's floor spikes paired particles? The dam break at 246k to frame 425, as
# shipped and with the drag out of the force condition (call 3's tree: 16c079e with scratch/glsl-dragout),
# its particles exported there. Run make-shaders.sh first (scratch/glsl-dragout, scratch/pairs.py).
set -u
scripts/gpu/setup-and-build.sh ranryu > $OUT/build.txt 2>&1 || { tail -30 $OUT/build.txt; exit 1; }
. scripts/gpu/env.sh x
dx=$(python3 scripts/gpu/scene-at.py dam-break $OUT/db.json 250000)
for v in base dragout; do
  sd=""; [ $v = dragout ] && sd="--shader-dir scratch/glsl-dragout"
  timeout 60 $B profile --scene $OUT/db.json --spacing $dx --shading particles --size 64x36 --frames 425 --warmup 0 $sd --checkpoint /tmp/ck-$v --records $OUT/rec-$v.csv --quiet > /tmp/p-$v.txt 2>&1
  echo "== $v profile rc $?"; grep -E "^simulation|fps and|^guard" /tmp/p-$v.txt
  timeout 40 $B record --resume /tmp/ck-$v --frames 1 --out /tmp/r-$v --export-particles ply --shading particles --size 64x36 $sd --quiet > /tmp/r-$v.txt 2>&1
  echo "== $v record rc $?"; ls /tmp/r-$v | tail -2
  timeout 60 python3 scratch/pairs.py $(ls /tmp/r-$v/particles_*.ply | tail -1) $dx | tee $OUT/pairs-$v.txt
done
