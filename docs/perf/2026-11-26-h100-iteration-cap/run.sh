#!/usr/bin/env bash
# Call A: the cap policy (next_iteration_cap) against HEAD's engine: 10 s of the dam break at 246k,
# and the tank at rest at 1M (rows) over 24 frames with each.
scripts/gpu/setup-and-build.sh ranryu >/dev/null 2>&1
. scripts/gpu/env.sh a-out
o=$out/a; mkdir -p "$o"
{ nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; date -u; } | tee "$o/device.txt"
start=$(date +%s)
(cd scratch/base && cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DRANRYU_WINDOW=OFF >/dev/null &&
  cmake --build build -j 16 --target ranryu >/dev/null) || { echo "base did not build"; exit 1; }
echo "base built in $(( $(date +%s) - start )) s"
base_bin=scratch/base/build/app/ranryu
passes='dfsph\.(density|boundary|divergence.solve|pressure.solve)|frame \(GPU|^simulation|density solve|fps and|^guard|^ranryu:'
dx=$(python3 scripts/gpu/scene-at.py dam-break "$o/db10-scene.json" 250000)
for v in base cap; do
  bin=$B; [ $v = base ] && bin=$base_bin
  f=$o/db10-$v
  timeout 150 "$bin" profile --scene "$o/db10-scene.json" --spacing "$dx" --shading particles --size 640x360 \
    --frames 600 --warmup 0 --records "$f.csv" > "$f.txt" 2>&1
  echo "== 10 s $v $dx: rc $? at $(( $(date +%s) - start )) s"
  grep -E "$passes" "$f.txt"
done
for v in base cap; do
  bin=$B; [ $v = base ] && bin=$base_bin
  RANRYU_BIN=$bin OUT=$o/tank-$v VARIANTS="rows:sph.boundary_rows=true" PARTICLES=1000000 FRAMES=24 RUN_TIMEOUT=120 \
    scripts/gpu/tank-fast.sh > /dev/null 2>&1
  echo "== tank 1M $v at $(( $(date +%s) - start )) s"
  cut -d, -f1,3,5,6,7,9,11 $o/tank-$v/tank-fast/rows-1000000.csv | tr '\n' ' '; echo
done
(cd "$out" && tar czf a.tgz a && rm -rf a)
