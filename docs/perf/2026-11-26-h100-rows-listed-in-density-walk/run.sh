#!/usr/bin/env bash
# Run on the GPU host from the repository root after scripts/gpu/setup-and-build.sh, with OUT set and
# scratch/base = `git archive b18ee5e -- . ":!docs/perf"` (the commit before the change) unpacked.
# The boundary rows listed in the density pass's walk instead of a pass of their own:
# the committed engine before it (scratch/base, built here) against the working tree.
. scripts/gpu/env.sh x
o=$OUT/l; mkdir -p $o
{ nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; date -u; git status --short | grep -v scratch; } > $o/device.txt
cat $o/device.txt
s=$(date +%s)
(cd scratch/base && cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DRANRYU_WINDOW=OFF >/dev/null && cmake --build build -j 16 --target ranryu >/dev/null) || echo "baseline build failed"
echo "baseline built in $(( $(date +%s) - s )) s"
BASE=scratch/base/build/app/ranryu
for dx in 0.005 0.00317 0.002; do
  for v in base listed; do
    bin=$B; [ $v = base ] && bin=$BASE
    f=$o/db-$v-$dx
    timeout 150 $bin profile --scene dam-break --spacing $dx --size 1920x1080 --frames 20 --warmup 20 --json $f.json > $f.txt 2>&1
    echo "== $v $dx rc $?"
    grep -E "dfsph\.(density|boundary|divergence.solve|pressure.solve)|frame \(GPU|^simulation|density solve|fps and" $f.txt
  done
done
for v in base listed; do
  bin=$B; [ $v = base ] && bin=$BASE
  f=$o/db10-$v
  dx=$(python3 scripts/gpu/scene-at.py dam-break $o/db10-scene.json 250000)
  timeout 120 $bin profile --scene $o/db10-scene.json --spacing $dx --shading particles --size 640x360 --frames 600 --warmup 0 --records $f.csv > $f.txt 2>&1
  echo "== 10 s $v $dx rc $?"
  grep -E "dfsph\.(density|boundary|divergence.solve|pressure.solve)|frame \(GPU|^simulation|density solve|fps and|^guard|^ranryu:" $f.txt
done
cd $OUT && tar czf l.tgz l && rm -rf l
