#!/usr/bin/env bash
# On the GPU host, after setup-and-build.sh: the dam break as shipped with another commit's engine
# against this tree's, in one call. The other engine is built here from BASE_DIR (default scratch/base),
# which the development machine fills before the call (the GPU host's copy has no history):
#     rm -rf scratch/base && mkdir -p scratch/base && git archive REV -- . ':!docs/perf' | tar x -C scratch/base
# Runs, each with both engines: frames 20-40 of the whole pipeline at 1920x1080 at every spacing of
# SPACINGS (default "0.005 0.00317 0.002": 64k, 246k and 1M particles), then TEN_S (default 1) ten
# simulated seconds at about 250k particles with particle shading at 640x360. Prints the DFSPH passes,
# the step counts and the rates; reports and records go to $OUT/compare (tarred as $OUT/compare.tgz).
#     TAG=after scripts/gpu/compare-engines.sh
. "$(dirname "$0")/env.sh" compare-out
o=$out/compare; mkdir -p "$o"
tag=${TAG:-new}
base_dir=${BASE_DIR:-scratch/base}
{ nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; date -u; } | tee "$o/device.txt"
start=$(date +%s)
(cd "$base_dir" && cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DRANRYU_WINDOW=OFF >/dev/null &&
  cmake --build build -j 16 --target ranryu >/dev/null) || { echo "the base engine in $base_dir did not build"; exit 1; }
echo "base built in $(( $(date +%s) - start )) s"
base_bin=$base_dir/build/app/ranryu
binary() { if [ "$1" = base ]; then echo "$base_bin"; else echo "$B"; fi; }
passes='dfsph\.(density|boundary|divergence.solve|pressure.solve)|frame \(GPU|^simulation|density solve|fps and|^guard|^ranryu:'
for dx in ${SPACINGS:-0.005 0.00317 0.002}; do
  for v in base "$tag"; do
    f=$o/db-$v-$dx
    timeout 150 "$(binary $v)" profile --scene dam-break --spacing "$dx" --size 1920x1080 --frames 20 --warmup 20 \
      --json "$f.json" > "$f.txt" 2>&1
    echo "== $v $dx: rc $?"
    grep -E "$passes" "$f.txt"
  done
done
if [ "${TEN_S:-1}" = 1 ]; then
  dx=$(python3 scripts/gpu/scene-at.py dam-break "$o/db10-scene.json" 250000)
  for v in base "$tag"; do
    f=$o/db10-$v
    timeout 150 "$(binary $v)" profile --scene "$o/db10-scene.json" --spacing "$dx" --shading particles --size 640x360 \
      --frames 600 --warmup 0 --records "$f.csv" > "$f.txt" 2>&1
    echo "== 10 s $v $dx: rc $?"
    grep -E "$passes" "$f.txt"
  done
fi
if [ -n "${OUT:-}" ]; then (cd "$out" && tar czf compare.tgz compare && rm -rf compare); fi
