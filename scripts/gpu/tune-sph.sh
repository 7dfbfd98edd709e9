#!/usr/bin/env bash
# Tuning experiments on the GPU host (docs/PERFORMANCE.md): the 1M-particle dam break with
# density/forces workgroup sizes varied through --shader-dir copies, and the radix sort with 4
# items per invocation (a second build). Prints ms per call of the passes that change.
set -uo pipefail
cd "$(dirname "$0")/../.."
run() {  # label, binary, extra args
  local label=$1 bin=$2; shift 2
  echo "== $label"
  $bin profile --scene dam-break --spacing 0.002 --size 320x180 --frames 6 --warmup 2 "$@" 2>&1 |
    awk '/^(sort\.|density|forces|integrate|reorder|hash)/ {printf "%-14s %s\n", $1, $6}'
}
B=build/gpu/app/ranryu
run baseline $B
for n in 64 256; do
  rm -rf /tmp/wg$n && cp -r glsl /tmp/wg$n
  sed -i "s/layout(local_size_x = 128) in;/layout(local_size_x = $n) in;/" /tmp/wg$n/sim/sph/compute_density.comp /tmp/wg$n/sim/sph/compute_forces.comp
  run "density/forces local size $n" $B --shader-dir /tmp/wg$n
done
rm -rf /tmp/items4 && mkdir -p /tmp/items4 && cp -r CMakeLists.txt cmake app engine glsl media tests /tmp/items4/
sed -i 's/#define RANRYU_SORT_RADIX_ITEMS_PER_THREAD 8/#define RANRYU_SORT_RADIX_ITEMS_PER_THREAD 4/' /tmp/items4/glsl/shared/bindings.h
grep -c "RADIX_ITEMS_PER_THREAD 4" /tmp/items4/glsl/shared/bindings.h
cmake -S /tmp/items4 -B /tmp/items4/build -G Ninja -DCMAKE_BUILD_TYPE=Release -DRANRYU_WINDOW=OFF -DRANRYU_TESTS=OFF >/dev/null
cmake --build /tmp/items4/build -j 16 --target ranryu >/dev/null 2>&1 || echo "items4 build failed"
run "radix 4 items per invocation" /tmp/items4/build/app/ranryu
run baseline-again $B
