#!/usr/bin/env bash
# Run from the repository root on the GPU host after scripts/gpu/setup-and-build.sh, with OUT set and
# scratch/v/{head,nobase,new}/glsl made first: head = `git archive cbf564d glsl` plus the new
# compute_wall_density.comp; new = the working tree of that day (the density solve's prepare reusing the
# divergence solve's base, not kept); nobase = new with every prepare whole (what was committed).
# The boundary rows' prepare passes: HEAD's shaders (the wall walked in both prepares), the wall
# density kept per boundary generation with each prepare whole (nobase), and with the density solve's
# prepare reusing the divergence solve's base (new). The dam break's frames 20-40 at 1920x1080, then 10 s at 246k.
. scripts/gpu/env.sh x
o=$OUT/r; mkdir -p $o
{ nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; date -u; git rev-parse HEAD; git status --short | grep -v scratch; } > $o/device.txt
cat $o/device.txt
for dx in 0.005 0.00317 0.002; do
  for v in head nobase new; do
    f=$o/db-$v-$dx
    timeout 200 $B profile --scene dam-break --spacing $dx --size 1920x1080 --frames 20 --warmup 20 --shader-dir scratch/v/$v/glsl \
      --json $f.json > $f.txt 2>&1
    echo "== $v $dx rc $?"
    grep -E "dfsph\.boundary|dfsph.density|pressure.solve|frame \(GPU|^simulation|fps and" $f.txt
  done
done
for v in head new; do
  f=$o/db10-$v
  dx=$(python3 scripts/gpu/scene-at.py dam-break $f.json 250000)
  timeout 150 $B profile --scene $f.json --spacing $dx --shading particles --size 640x360 --frames 600 --warmup 0 \
    --shader-dir scratch/v/$v/glsl --records $f.csv > $f.txt 2>&1
  echo "== 10 s $v $dx rc $?"
  grep -E "dfsph\.boundary|dfsph.density|pressure.solve|frame \(GPU|^simulation|density solve|fps and|^guard|^ranryu:" $f.txt
done
cd $OUT && tar czf r.tgz r && rm -rf r
